#pragma once

// The flight plan being uploaded, shared by the GUI thread, which starts and
// cancels it, and the link thread, which asks it for each frame's BLOCK 2
// section and gives it every BLOCK 2 the aircraft sends back. One mutex
// guards the uploader; it is held for a section's copy, never across I/O, so
// neither thread waits on the other for longer than that.
//
// Plug it into the link with linkOptions(); the object must outlive the
// LinkController it was given to. The link decides the section size: 215 data
// bytes, or 199 on a secure link, whose BLOCK 2 keeps 16 bytes of checked
// padding (codec/secure/SecureCodec.h); a 215-byte section there would be refused by
// the encoder, frame after frame, and the upload would never progress.

#include "codec/message/FlightPlanTransfer.h"
#include "link/session/LinkWorker.h"

#include <QByteArray>
#include <QElapsedTimer>
#include <QMutex>
#include <QObject>

#include <memory>

class FlightPlanUpload : public QObject {
    Q_OBJECT

public:
    enum class State { Idle, Sending, Acknowledged, GaveUp, Cancelled };
    Q_ENUM(State)

    struct Progress {
        State state = State::Idle;
        quint32 planId = 0;
        int sent = 0;    // distinct sections sent at least once
        int total = 0;   // sections in the plan
        int inPass = 0;  // sections of the current pass sent
        int pass = 0;    // 1 during the first pass
        int maxPasses = 0;
        // Seconds between the last sections sent, as the link really sends
        // them (a second a frame, or slower when the link falls behind),
        // once two have gone.
        bool rateMeasured = false;
        double secondsPerSection = 0;
        // Acknowledged: what the aircraft said the plan holds
        // (codec/plan/PlanContents.h Report); empty when it said nothing.
        QByteArray report;

        // Seconds until this pass ends and until the last pass ends, at the
        // measured rate or, before there is one, at `nominal` seconds a section.
        double secondsLeftInPass(double nominal) const;
        double secondsLeftAtMost(double nominal) const;
        friend bool operator==(const Progress&, const Progress&) = default;
    };

    // Passes over the whole plan before giving up unacknowledged.
    static constexpr int kMaxPasses = 5;

    explicit FlightPlanUpload(QObject* parent = nullptr);
    ~FlightPlanUpload() override;

    // Starts sending `plan` under a new flight_plan_ID, replacing any upload
    // in progress. False, with the reason, when the plan cannot be cut into
    // sections (too long).
    bool start(const QByteArray& plan, QString* error = nullptr);
    void cancel();
    Progress progress() const;

    // Options whose BLOCK 2 hooks call next() and handleReply() below. Uploads
    // started from now on use the section size of that link (options.secure).
    LinkWorker::Options linkOptions(LinkWorker::Options options = {});
    // Data bytes per section for the link last given to linkOptions().
    int sectionSize() const;

    // Link thread: the section for the next frame, and the aircraft's BLOCK 2.
    std::optional<rcm::FlightPlanSection> next();
    void handleReply(const rcm::FlightPlanSection& reply);

signals:
    // From whichever thread changed it; queued to the GUI by the connection.
    void progressChanged(const FlightPlanUpload::Progress& progress);

private:
    Progress progressLocked() const;
    void measureSection();

    mutable QMutex m_mutex;
    std::unique_ptr<rcm::FlightPlanUploader> m_uploader;
    State m_state = State::Idle;
    quint32 m_lastPlanId = 0;
    std::size_t m_sectionSize = rcm::FlightPlanSection::kMaxData;
    QElapsedTimer m_clock;
    qint64 m_lastSectionNs = -1;
    bool m_rateMeasured = false;
    double m_secondsPerSection = 0;
};

Q_DECLARE_METATYPE(FlightPlanUpload::Progress)
