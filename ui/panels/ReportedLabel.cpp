#include "ui/panels/ReportedLabel.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"
#include "ui/panels/ReportedState.h"

namespace {

const QString kNothing = QStringLiteral("\u2014");  // an em dash: nothing reported yet

// Dark text on amber: readable in daylight on a field laptop, and not the red
// the console keeps for link loss.
const QString kMismatchStyle = QStringLiteral("QLabel { background-color: #ffbf00; color: black; }");

}  // namespace

ReportedLabel::ReportedLabel(const CommandState* command, const ReportedState* reported, UnitRef ref, rcm::ItemId id,
                             int field, QWidget* parent)
    : QLabel(parent), m_command(command), m_reported(reported), m_ref(ref), m_id(id), m_field(field)
{
    setObjectName(QStringLiteral("reported:") + ItemText::name(id, field));
    setAccessibleName(tr("Reported %1").arg(ItemText::label(id, field)));
    setMinimumWidth(fontMetrics().horizontalAdvance(QStringLiteral("RETRACTED")));
    setTextInteractionFlags(Qt::TextSelectableByMouse);
    setProperty("mismatch", false);
    refresh();
    connect(reported, &ReportedState::updated, this, &ReportedLabel::refresh);
    connect(command, &CommandState::changed, this, &ReportedLabel::refresh);
}

void ReportedLabel::refresh()
{
    auto text = [this](const rcm::Value* v) {
        if (!v)
            return kNothing;
        return m_field < 0 ? ItemText::value(m_id, *v) : ItemText::fieldValue(m_id, m_field, *v);
    };
    const rcm::Value* reported = m_reported->value(m_ref, m_id);
    setText(text(reported));

    const int frames = m_reported->mismatchFrames(m_ref, m_id, m_field);
    const bool mismatch = frames > ReportedState::kTransientFrames;
    if (mismatch != property("mismatch").toBool()) {
        setProperty("mismatch", mismatch);
        setStyleSheet(mismatch ? kMismatchStyle : QString());
    }
    const QString what = ItemText::label(m_id, m_field);
    if (mismatch)
        setToolTip(tr("%1: commanded %2, reported %3 for %n status frames", nullptr, frames)
                       .arg(what, text(m_command->value(m_ref, m_id)), text(reported)));
    else
        setToolTip(tr("%1 as the aircraft last reported it").arg(what));
}
