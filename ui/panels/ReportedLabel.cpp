#include "ui/panels/ReportedLabel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/ReportedState.h"

#include <QAction>
#include <QClipboard>
#include <QGuiApplication>

#include <algorithm>

namespace {

const QString kNothing = QStringLiteral("\u2014");  // an em dash: nothing reported yet

// Dark text on amber: readable in daylight on a field laptop, and not the red
// the console keeps for link loss.
const QString kMismatchStyle = QStringLiteral("QLabel { background-color: #ffbf00; color: black; }");
// Stale: what the aircraft said some seconds ago. Italic in a dashed frame, in
// the theme's own text colour, so that it reads in the night theme too.
const QString kStaleStyle = QStringLiteral("QLabel { font-style: italic; border: 1px dashed palette(text); }");
const QString kStaleMismatchStyle =
    QStringLiteral("QLabel { background-color: #ffbf00; color: black; font-style: italic; border: 1px dashed black; }");

}  // namespace

ReportedLabel::ReportedLabel(const CommandState* command, const ReportedState* reported, UnitRef ref, rcm::ItemId id,
                             int field, QWidget* parent)
    : SteadyLabel(parent), m_command(command), m_reported(reported), m_ref(ref), m_id(id), m_field(field)
{
    setObjectName(QStringLiteral("reported:") + ItemText::name(id, field));
    setAccessibleName(tr("Reported %1").arg(ItemText::label(id, field)));
    // Room for the value commanded now, too: the first status frame mostly
    // reports what was commanded, and a dozen labels growing at once lays
    // out their cards again and repaints them whole.
    setMinimumWidth(std::max(fontMetrics().horizontalAdvance(QStringLiteral("RETRACTED")),
                             fontMetrics().horizontalAdvance(valueText(command->value(ref, id)))));
    // Copied from its context menu rather than selected with the mouse: a
    // selectable label lays its text out as a rich-text document, about half
    // a millisecond of the GUI thread per new value, and a status frame can
    // bring forty new values at once.
    auto* copy = new QAction(tr("Copy"), this);
    connect(copy, &QAction::triggered, this, [this] { QGuiApplication::clipboard()->setText(text()); });
    addAction(copy);
    setContextMenuPolicy(Qt::ActionsContextMenu);
    setProperty("mismatch", false);
    setProperty("stale", false);
    refresh();
    connect(reported, &ReportedState::updated, this, &ReportedLabel::refresh);
    connect(command, &CommandState::changed, this, &ReportedLabel::refresh);
}

void ReportedLabel::setAgeShown(bool shown)
{
    if (shown == m_ageShown)
        return;
    m_ageShown = shown;
    m_shown.reset();
    refresh();
}

QString ReportedLabel::valueText(const rcm::Value* value) const
{
    if (!value)
        return kNothing;
    return m_field < 0 ? ItemText::value(m_id, *value) : ItemText::fieldValue(m_id, m_field, *value, m_command->unit(m_ref));
}

void ReportedLabel::refresh()
{
    const auto text = [this](const rcm::Value* v) { return valueText(v); };
    const rcm::Value* reported = m_reported->value(m_ref, m_id);
    const auto age = reported ? m_reported->staleAge() : std::nullopt;
    const int seconds = age ? static_cast<int>(age->count()) : 0;
    const int frames = m_reported->mismatchFrames(m_ref, m_id, m_field);
    const bool mismatch =
        frames > ReportedState::kTransientFrames || m_reported->mismatchWhileStale(m_ref, m_id, m_field);
    const bool stale = age.has_value();
    const rcm::Value* commandedValue = m_command->value(m_ref, m_id);
    const Facts facts{reported ? std::optional(*reported) : std::nullopt,
                      commandedValue ? std::optional(*commandedValue) : std::nullopt,
                      stale ? std::optional(seconds) : std::nullopt, frames, mismatch};
    if (facts == m_shown)
        return;
    m_shown = facts;
    setText(age && m_ageShown ? tr("%1 (stale, %2 s)").arg(text(reported)).arg(seconds) : text(reported));

    if (mismatch != property("mismatch").toBool() || stale != property("stale").toBool()) {
        setProperty("mismatch", mismatch);
        setProperty("stale", stale);
        setStyleSheet(mismatch ? (stale ? kStaleMismatchStyle : kMismatchStyle) : stale ? kStaleStyle : QString());
    }
    const QString what = ItemText::label(m_id, m_field);
    const QString commanded = text(commandedValue);
    if (mismatch && stale)
        setToolTip(
            tr("%1: commanded %2, last reported %3 %n s ago; no status frame since to confirm it", nullptr, seconds)
                .arg(what, commanded, text(reported)));
    else if (mismatch)
        setToolTip(tr("%1: commanded %2, reported %3 for %n status frames", nullptr, frames)
                       .arg(what, commanded, text(reported)));
    else if (stale)
        setToolTip(tr("%1 as the aircraft reported it %n s ago; no status frame since", nullptr, seconds).arg(what));
    else
        setToolTip(tr("%1 as the aircraft last reported it").arg(what));
}
