#pragma once

// A read-only session from the broker: what a console publishes for one
// aircraft (SessionPublisher, BrokerTopics.h), told as the link's own events,
// so that the console binds the same widgets to it as to a live link. It
// subscribes to rcm/<aircraft>/# and says
//   - frameLogged for each frame of the followed station, up and down, with
//     its bytes (offset -1: in no file of ours); frameSent for the ones up;
//   - messageReceived for each status, read back from the frame's text with
//     the codec's text format parser, and for the retained last status on
//     joining;
//   - statisticsChanged and stateChanged from the followed station's
//     retained statistics, with linkLost and linkRegained on their changes;
//     the link is lost to us too when the broker goes away or the followed
//     station goes offline;
//   - errorOccurred for the broker's trouble and the followed station's
//     events of severity "error" or "alarm", transportStatusChanged for the
//     others, for joining and for the broker's return.
// It has no way to send anything to the aircraft, nor to publish.
//
// What it shows is verified (BrokerTrust, docs/security.md "The broker"):
// only messages signed by the key trusted for their station, each newer than
// the last of its station on its topic, drive the window. A message refused
// (forged, unsigned in a trusted station's name, replayed, malformed, too
// large) is said by messageRefused(), for the console to count as it counts
// refused frames. A station whose key is not trusted is unverified: listed,
// said once, never followed, its reports never shown as control. A keyed
// station's session without its key is sealed: all there is to say is that
// it exists.
//
// The followed station is the one set by followStation(); else the
// verified online station whose report says "control"; else the first
// verified station a frame came from.
//
// Nothing is missed silently: the broker keeps the observer's session while
// it is away (a persistent session, QoS 1), a station's frames are numbered
// (FrameReport::seq), and frames that never came are said by warning()
// ("missed 12 frames of GB_30226").

#include "link/broker/BrokerEnvelope.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/SequenceCheck.h"
#include "link/clock/Clock.h"
#include "link/session/Observation.h"

#include <QHash>
#include <QMap>
#include <QSet>
#include <QString>
#include <QStringList>

#include <memory>
#include <optional>

class MqttClient;

class BrokerObservation : public Observation {
    Q_OBJECT

public:
    // Observes settings.aircraft ("unknown" when empty), believing
    // settings.trust (none: every station is unverified). Without a client
    // ID one is made up ("rcm-observer-GB_133-1a2b3c4d"): the broker keeps
    // the session under it while the observer is away. The client's outages
    // are timed on `clock`, the session's (null: the SystemClock).
    explicit BrokerObservation(const BrokerSettings& settings, QObject* parent = nullptr,
                               std::shared_ptr<Clock> clock = nullptr);
    ~BrokerObservation() override;

    void start() override;
    void stop() override;

    QString aircraft() const { return m_aircraft; }
    QString observed() const override { return m_aircraft; }
    bool isConnected() const;
    const BrokerSettings& settings() const;
    MqttClient* client() const { return m_client; }

    // Every verified station that has a report for the aircraft, by station ID.
    const QMap<QString, StationReport>& stations() const { return m_stations; }
    // Stations heard whose key is not trusted: never followed, never shown as control.
    QStringList unverifiedStations() const;
    // Verified stations whose keyed session no key of ours opens, with the
    // link key's fingerprint.
    const QMap<QString, QString>& sealedStations() const { return m_sealed; }

    // Empty: choose as the header says.
    void followStation(const QString& station);
    QString followedStation() const;

    // The last statistics received (state Lost while the broker is away).
    std::optional<LinkStatistics> statistics() const { return m_statistics; }

    quint64 refusedMessages() const { return m_refused; }
    quint64 missedFrames() const { return m_missedFrames; }

signals:
    void stationsChanged();
    void eventReported(const EventReport& event);
    // A message refused: "forged: GB_30226's signature does not verify on ...".
    void messageRefused(const QString& reasonAndDetail);
    // Worth the operator's knowing, nothing failed here: frames missed, a
    // station unverified or sealed.
    void warning(const QString& message);

private:
    void messageOpened(const OpenedMessage& message);
    void brokerConnected();
    void brokerDisconnected();
    void stationReported(const OpenedMessage& message);
    void frameReported(const OpenedMessage& message);
    // The report a message holds; or nothing, the message refused as
    // "unreadable: <station>'s <what>: <why>".
    template <typename Report>
    std::optional<Report> readReport(const OpenedMessage& message, const char* what);
    // A state or statistics report kept as its station's newest, and applied
    // when that station is the one followed.
    template <typename Report>
    void keepNewest(const OpenedMessage& message, const char* what, QHash<QString, Report>& newest,
                    void (BrokerObservation::*apply)(const Report&));
    void eventArrived(const OpenedMessage& message);
    void followedChanged();
    void applyStats(const StatsReport& stats);
    void applyState(const StateReport& state);
    void emitMessage(const QString& text, qint64 utcMicros, rcm::Corrections corrected, FrameTransport transport,
                     const QString& from);
    void setLinkState(LinkState state);
    void reportError(const QString& message);
    void refuse(const QString& reasonAndDetail);
    void noteUnverified(const QString& station);
    void noteSealed(const QString& station, const QString& fingerprint);

    MqttClient* m_client;
    QString m_aircraft;
    QString m_followed;        // set by followStation()
    QString m_firstFrameFrom;  // the first verified station a frame came from
    QString m_lastFollowed;    // followedStation() when last looked at
    QMap<QString, StationReport> m_stations;  // verified
    QSet<QString> m_unverified;
    QMap<QString, QString> m_sealed;  // station -> link key fingerprint
    SequenceCheck m_sequence;
    // The followed station's frames: the session and the number of the last one told.
    struct FrameRun {
        qint64 session = 0;
        quint64 last = 0;
    };
    QHash<QString, FrameRun> m_frameRuns;  // by station
    // Each verified station's newest state and statistics, told when it is the followed one.
    QHash<QString, StateReport> m_states;
    QHash<QString, StatsReport> m_stats;
    std::optional<LinkStatistics> m_statistics;
    LinkState m_state = LinkState::Closed;
    std::optional<rcm::Message> m_lastMessage;  // the last status told, not to tell it twice
    QString m_lastError;                        // not to repeat one unreadable payload's error
    quint64 m_refused = 0;
    quint64 m_missedFrames = 0;
    bool m_started = false;
};
