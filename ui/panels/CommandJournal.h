// Every change the operator makes to the command, for the event log: when
// (the event's time), by which station, in which unit and item, from what to
// what; then the frame that first carried it and whether the aircraft's
// status reports confirmed it within kConfirmFrames status frames. A change
// made while the command is held waits for commanding to resume.
//
// No I/O: the window gives it the command's edits, the frames sent and the
// status frames received, and writes what it says into the event log.
#pragma once

#include "codec/message/CommandChanges.h"
#include "codec/message/Message.h"
#include "link/session/MessageMetaType.h"

#include <QObject>
#include <QString>

#include <optional>
#include <vector>

class CommandState;

class CommandJournal : public QObject {
    Q_OBJECT

public:
    // Status frames, counted from the first after the frame that carried a
    // change, within which the aircraft must report it: the landing gear
    // takes 3.5 s to move, a surface at 10 degrees a second up to 25 s.
    static constexpr int kConfirmFrames = 30;

    // `command` must outlive it.
    explicit CommandJournal(const CommandState* command, QObject* parent = nullptr);

    // This console's station ("GB_30226"), or empty: who made the changes.
    void setStation(const QString& station) { m_station = station; }
    // Changes not yet confirmed or refuted.
    int pending() const { return static_cast<int>(m_pending.size()); }

public slots:
    // A frame carrying the command went out (not one held back).
    void frameSent(quint32 messageId);
    void statusReceived(const rcm::Message& status);
    // The link ended: what was not confirmed is said so, and forgotten.
    void linkEnded();

signals:
    // One line for the event log; `confirmed` false for a warning.
    void entry(const QString& text, bool warning);

private:
    struct Pending {
        rcm::ItemChange change;
        std::optional<quint32> sentIn;  // the first frame that carried it
        int statusFrames = 0;           // status frames since it was sent
    };

    void edited(const rcm::Message& before);
    QString by() const;

    const CommandState* m_command;
    QString m_station;
    std::vector<Pending> m_pending;
};
