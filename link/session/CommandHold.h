#pragma once

// Whether the console's frames carry its command, or hold it back until the
// operator resumes (docs/protocol.md section 10, "What a console sends").
// Every frame carries the whole commanded state, so a console that starts,
// connects, reconnects after a loss, loads another airframe or is given
// control must not send what its panels happen to hold: until the operator
// has seen the aircraft's report and resumed, its frames carry the header
// alone (rcm::heldCommand), which the aircraft reads as "keep everything".
//
// A hold that adopts the report takes the first status frame after it into
// the command (rcm::withValuesOf): the panels then show what the aircraft
// does, and the differences from what they held are kept for the operator.
// A hold after a link loss does not: the panels keep what the operator
// commanded, and the differences from the report are shown instead.
//
// No I/O and no widgets: ConsoleSession owns it and feeds it.

#include "codec/message/CommandChanges.h"
#include "codec/message/Message.h"

#include <QObject>
#include <QString>

#include <optional>
#include <vector>

class CommandHold : public QObject {
    Q_OBJECT

public:
    enum class Reason {
        NewLink,       // a link was started (connect, rehearsal, a link replacing another)
        LinkRegained,  // the link came back after a loss (a redial, an outage) and the report differs
        Airframe,      // the operator loaded another airframe
        ControlGiven,  // the aircraft gave control to this station (handover, failover)
        NotInControl,  // another station is in control: this station's frames command nothing
    };
    Q_ENUM(Reason)

    explicit CommandHold(QObject* parent = nullptr);

    bool holding() const { return m_holding; }
    Reason reason() const { return m_reason; }
    // For people: "Holding commands: a new link" ...
    static QString reasonText(Reason reason);
    // A status frame has been delivered since the hold began.
    bool reportHeard() const { return m_report.has_value(); }
    // The aircraft's last status frame, on this link; none before the first.
    const std::optional<rcm::Message>& lastReport() const { return m_lastReport; }
    // How the report differed from the command when it first came in the
    // hold (before it was adopted, when the hold adopts it).
    const std::vector<rcm::ItemChange>& differences() const { return m_differences; }

    // Holds from now on. With `adopt`, the next status frame becomes the
    // command (statusReceived() returns it). A new reason replaces the old.
    void hold(Reason reason, bool adopt);
    // Frames carry the command again: the operator confirmed.
    void resume();
    // The link ended: a new one starts with no report.
    void forgetReports();

    // A status frame delivered while `command` is what the console would
    // send. Returns the command to adopt, when this hold adopts and this is
    // its first report.
    std::optional<rcm::Message> statusReceived(const rcm::Message& status, const rcm::Message& command);

signals:
    // holding(), reason(), reportHeard() or differences() changed.
    void changed();

private:
    bool m_holding = true;
    Reason m_reason = Reason::NewLink;
    bool m_adopt = true;
    std::optional<rcm::Message> m_report;      // the first since the hold began
    std::optional<rcm::Message> m_lastReport;  // the latest on this link
    std::vector<rcm::ItemChange> m_differences;
};
