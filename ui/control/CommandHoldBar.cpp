#include "ui/control/CommandHoldBar.h"

#include "codec/message/CommandChanges.h"
#include "link/session/ConsoleSession.h"
#include "ui/alerts/Confirmation.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

namespace {

// Dark text on amber in both themes: a state to act on, not an error.
const char* const kStyle =
    "CommandHoldBar { background-color: #ffe9a8; border: 2px solid #b26a00; border-radius: 3px; }"
    "CommandHoldBar QLabel { color: #3d2600; background: transparent; }";

// As many lines as a dialog or the band shows; the rest counted.
constexpr int kShownDifferences = 12;

QStringList firstLines(const std::vector<rcm::ItemChange>& changes, const QString& format)
{
    QStringList lines;
    for (const rcm::ItemChange& c : changes) {
        if (lines.size() == kShownDifferences) {
            lines << CommandHoldBar::tr("\u2026 and %n more", nullptr, int(changes.size()) - kShownDifferences);
            break;
        }
        lines << format.arg(ItemText::changeWhere(c), ItemText::changeValue(c, c.from), ItemText::changeValue(c, c.to));
    }
    return lines;
}

}  // namespace

CommandHoldBar::CommandHoldBar(ConsoleSession* session, const CommandState* command, QWidget* parent)
    : QFrame(parent), m_session(session), m_command(command), m_text(new QLabel), m_resume(new QPushButton)
{
    setObjectName(QStringLiteral("commandHold"));
    setStyleSheet(QString::fromLatin1(kStyle));
    m_text->setWordWrap(true);
    m_text->setTextFormat(Qt::PlainText);
    // Never the focus: a stray Space or Enter must not resume commanding.
    m_resume->setFocusPolicy(Qt::NoFocus);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(8, 4, 8, 4);
    layout->addWidget(m_text, 1);
    layout->addWidget(m_resume, 0, Qt::AlignTop);
    connect(m_resume, &QPushButton::clicked, this, &CommandHoldBar::requestResume);
    connect(session->commandHold(), &CommandHold::changed, this, &CommandHoldBar::refresh);
    connect(session->stationControl(), &StationControl::roleChanged, this, &CommandHoldBar::refresh);
    connect(session, &ConsoleSession::linkStarted, this, &CommandHoldBar::refresh);
    connect(session, &ConsoleSession::linkStopped, this, &CommandHoldBar::refresh);
    refresh();
}

QString CommandHoldBar::text() const
{
    return m_text->text();
}

QStringList CommandHoldBar::differencesNow(int* count) const
{
    const std::optional<rcm::Message>& report = m_session->commandHold()->lastReport();
    const std::vector<rcm::ItemChange> changes =
        report ? rcm::commandChanges(*report, m_command->message()) : std::vector<rcm::ItemChange>{};
    *count = int(changes.size());
    return firstLines(changes, tr("%1: the aircraft reports %2, the panels say %3"));
}

void CommandHoldBar::refresh()
{
    const CommandHold* hold = m_session->commandHold();
    const bool live = m_session->kind() == ConsoleSession::Kind::Live ||
                      m_session->kind() == ConsoleSession::Kind::Rehearsal;
    const bool shown = live && hold->holding();
    setVisible(shown);
    if (!shown)
        return;
    const StationControl* control = m_session->stationControl();
    const bool takes = control->role() == StationControl::Role::Offered;
    m_resume->setText(takes ? tr("Take control\u2026") : tr("Resume commanding\u2026"));

    QStringList lines;
    lines << tr("Commands held: %1. The frames carry no command: the aircraft keeps what it does.")
                 .arg(CommandHold::reasonText(hold->reason()));
    if (!hold->reportHeard()) {
        lines << tr("Waiting for the aircraft's report.");
    } else if (hold->reason() == CommandHold::Reason::LinkRegained) {
        lines << tr("The aircraft reports %n item(s) differently from the panels:", nullptr,
                    int(hold->differences().size()));
        lines << firstLines(hold->differences(), tr("  %1: panels %2, aircraft %3"));
    } else if (hold->differences().empty()) {
        lines << tr("The aircraft's report is in the panels; it agreed with what they held.");
    } else {
        lines << tr("The aircraft's report is in the panels. What they held before differed in %n item(s):", nullptr,
                    int(hold->differences().size()));
        lines << firstLines(hold->differences(), tr("  %1: was %2, the aircraft reports %3"));
    }
    QString whyNot;
    bool can = true;
    switch (control->role()) {
        case StationControl::Role::Unknown:
            can = !control->station().has_value();
            whyNot = tr("The aircraft has not said yet which station is in control");
            break;
        case StationControl::Role::Backup:
        case StationControl::Role::Observing:
            can = false;
            whyNot = tr("Another station is in control: this station can only watch");
            break;
        case StationControl::Role::HandingOver:
            can = false;
            whyNot = tr("Handing control over");
            break;
        default:
            break;
    }
    if (!can)
        lines << whyNot + QLatin1Char('.');
    m_text->setText(lines.join(QLatin1Char('\n')));
    m_resume->setEnabled(can);
    m_resume->setToolTip(can ? (takes ? tr("Take control: the aircraft acts on this console's panels from the next "
                                           "frame (asks first, listing what differs from its report)")
                                      : tr("The frames carry the panels' command again from the next one (asks first, "
                                           "listing what differs from the aircraft's report)"))
                             : whyNot);
}

void CommandHoldBar::requestResume()
{
    const bool takes = m_session->stationControl()->role() == StationControl::Role::Offered;
    int count = 0;
    const QStringList differences = differencesNow(&count);
    Confirmation ask;
    ask.title = takes ? tr("Take control") : tr("Resume commanding");
    ask.text = takes ? tr("Take control and command the aircraft from this console's panels?")
                     : tr("Command the aircraft from this console's panels again?");
    if (!m_session->commandHold()->lastReport())
        ask.informativeText = tr("Nothing has been heard from the aircraft on this link: the panels' command may "
                                 "differ from what it does, and every item of it takes effect from the next frame.");
    else if (count == 0)
        ask.informativeText = tr("The panels agree with what the aircraft reports: nothing it does changes.");
    else
        ask.informativeText =
            tr("From the next frame the aircraft acts on the panels. They differ from its report in %n item(s):",
               nullptr, count) +
            QLatin1Char('\n') + differences.join(QLatin1Char('\n'));
    ask.action = takes ? tr("Take control") : tr("Resume commanding");
    if (!ask.ask(this))
        return;
    QString whyNot;
    if (!m_session->resumeCommanding(&whyNot))
        emit refused(tr("Not resumed: %1").arg(whyNot));
}
