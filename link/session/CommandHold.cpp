#include "link/session/CommandHold.h"

CommandHold::CommandHold(QObject* parent) : QObject(parent) {}

QString CommandHold::reasonText(Reason reason)
{
    switch (reason) {
        case Reason::NewLink:
            return tr("a new link");
        case Reason::LinkRegained:
            return tr("the link came back and the aircraft reports something else");
        case Reason::Airframe:
            return tr("another airframe was loaded");
        case Reason::ControlGiven:
            return tr("the aircraft gave control to this station");
        case Reason::NotInControl:
            return tr("another station is in control");
    }
    return {};
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
