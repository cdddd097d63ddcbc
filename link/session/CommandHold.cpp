#include "link/session/CommandHold.h"

#include "link/common/NameTable.h"

namespace {

// The reasons in words, for reasonText().
constexpr auto kReasonTexts = std::to_array<Named<CommandHold::Reason>>({
    {CommandHold::Reason::NewLink, QT_TRANSLATE_NOOP("CommandHold", "a new link")},
    {CommandHold::Reason::LinkRegained,
     QT_TRANSLATE_NOOP("CommandHold", "the link came back and the aircraft reports something else")},
    {CommandHold::Reason::Airframe, QT_TRANSLATE_NOOP("CommandHold", "another airframe was loaded")},
    {CommandHold::Reason::ControlGiven, QT_TRANSLATE_NOOP("CommandHold", "the aircraft gave control to this station")},
    {CommandHold::Reason::NotInControl, QT_TRANSLATE_NOOP("CommandHold", "another station is in control")},
});

}  // namespace

CommandHold::CommandHold(QObject* parent) : QObject(parent) {}

QString CommandHold::reasonText(Reason reason)
{
    return tr(nameOf(kReasonTexts, reason));
}

void CommandHold::hold(Reason reason, bool adopt)
{
    m_holding = true;
    m_reason = reason;
    m_adopt = adopt;
    m_report.reset();
    m_differences.clear();
    emit changed();
}

void CommandHold::resume()
{
    if (!m_holding)
        return;
    m_holding = false;
    emit changed();
}

void CommandHold::forgetReports()
{
    m_lastReport.reset();
    m_report.reset();
    m_differences.clear();
}

std::optional<rcm::Message> CommandHold::statusReceived(const rcm::Message& status, const rcm::Message& command)
{
    m_lastReport = status;
    if (!m_holding || m_report)
        return std::nullopt;
    m_report = status;
    m_differences = rcm::commandChanges(command, status);
    std::optional<rcm::Message> adopted;
    if (m_adopt)
        adopted = rcm::withValuesOf(command, status);
    emit changed();
    return adopted;
}
