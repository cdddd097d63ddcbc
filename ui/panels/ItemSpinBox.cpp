#include "ui/panels/ItemSpinBox.h"

#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QSignalBlocker>

#include <cmath>

ItemSpinBox::ItemSpinBox(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent)
    : QDoubleSpinBox(parent), m_command(command), m_ref(ref), m_id(id)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    setObjectName(ItemText::name(id));
    setDecimals(static_cast<int>(std::lround(std::log10(info.scale))));
    setRange(static_cast<double>(info.min) / info.scale, static_cast<double>(info.max) / info.scale);
    setSingleStep(1.0);
    if (!info.unit.empty())
        setSuffix(QLatin1Char(' ') + QString::fromUtf8(info.unit.data(), static_cast<qsizetype>(info.unit.size())));
    setToolTip(ItemText::toolTip(id));
    setAccessibleName(ItemText::label(id));
    setKeyboardTracking(false);
    setAlignment(Qt::AlignRight);
    refresh();
    connect(this, &QDoubleSpinBox::valueChanged, this, &ItemSpinBox::commit);
    connect(command, &CommandState::changed, this, &ItemSpinBox::refresh);
}

void ItemSpinBox::refresh()
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    setEnabled(v != nullptr);
    if (!v)
        return;
    const double shown = static_cast<double>(v->number) / rcm::itemInfo(m_id).scale;
    // Only a real difference: a spin box being typed in keeps its text.
    if (shown != value()) {
        const QSignalBlocker block(this);
        setValue(shown);
    }
}

void ItemSpinBox::commit(double shown)
{
    const auto number = std::llround(shown * rcm::itemInfo(m_id).scale);
    if (!m_command->setNumber(m_ref, m_id, number))
        refresh();
}
