#include "ui/panels/StationEditor.h"

#include "codec/message/CountryCodes.h"
#include "codec/message/ValueCodec.h"
#include "ui/panels/CommandGate.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/DeliberateInput.h"
#include "ui/panels/ItemText.h"

#include <QApplication>
#include <QFocusEvent>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QRegularExpressionValidator>
#include <QSignalBlocker>
#include <QStyle>
#include <QStyleOptionFrame>

#include <algorithm>
#include <limits>

namespace {

QString countryToolTip()
{
    return StationEditor::tr("ISO 3166 alpha-2 (GB) or dialling code (44); country and unit empty: not sent");
}

QString unitToolTip()
{
    return StationEditor::tr("Unit number, 0..65535");
}

constexpr int kUnitMax = std::numeric_limits<std::uint16_t>::max();

// Wide enough for the widest entry the validator lets through ("WW", four
// digits such as 1929) and for the placeholder, with the frame and margins the
// style gives a line edit: a fixed guess in pixels cut the placeholder off.
int fieldWidth(const QLineEdit* edit, const QStringList& samples)
{
    const QFontMetrics metrics = edit->fontMetrics();
    int text = 0;
    for (const QString& sample : samples + QStringList{edit->placeholderText()})
        text = std::max(text, metrics.horizontalAdvance(sample));
    // QLineEdit's own sizeHint() adds 2 * 2 px of inner margin to the text.
    const QMargins margins = edit->textMargins() + edit->contentsMargins();
    QStyleOptionFrame option;
    option.initFrom(edit);
    option.lineWidth = edit->style()->pixelMetric(QStyle::PM_DefaultFrameWidth, &option, edit);
    const QSize content(text + 4 + margins.left() + margins.right(), metrics.height());
    return edit->style()->sizeFromContents(QStyle::CT_LineEdit, &option, content, edit).width() + 2;
}

}  // namespace

StationEditor::StationEditor(CommandState* command, UnitRef ref, rcm::ItemId id, QWidget* parent)
    : QWidget(parent),
      m_command(command),
      m_ref(ref),
      m_id(id),
      m_country(new QLineEdit(this)),
      m_unit(new QLineEdit(this))
{
    setObjectName(ItemText::name(id));
    setAccessibleName(ItemText::label(id));
    setToolTip(ItemText::toolTip(id));
    setProperty("incomplete", false);
    setProperty("edited", false);
    m_country->setObjectName(QStringLiteral("country"));
    // Empty means the item is not sent, which is what the placeholder says;
    // the tooltip says what to type.
    m_country->setPlaceholderText(tr("none"));
    m_country->setToolTip(countryToolTip());
    m_country->setAccessibleName(tr("%1 country").arg(ItemText::label(id)));
    m_country->setValidator(
        new QRegularExpressionValidator(QRegularExpression(QStringLiteral("[A-Za-z]{0,2}|[0-9]{0,4}")), m_country));
    m_country->setMaxLength(4);
    m_country->setFixedWidth(fieldWidth(m_country, {QStringLiteral("WW"), QStringLiteral("0000")}));
    m_unit->setObjectName(QStringLiteral("unit"));
    m_unit->setPlaceholderText(tr("unit"));
    m_unit->setToolTip(unitToolTip());
    m_unit->setAccessibleName(tr("%1 unit number").arg(ItemText::label(id)));
    m_unit->setValidator(new QRegularExpressionValidator(QRegularExpression(QStringLiteral("[0-9]{0,5}")), m_unit));
    m_unit->setMaxLength(5);
    m_unit->setAlignment(Qt::AlignRight);
    m_unit->setFixedWidth(fieldWidth(m_unit, {QStringLiteral("00000")}));
    for (QLineEdit* field : {m_country, m_unit}) {
        field->setProperty("invalid", false);
        DeliberateInput::protect(field);
        connect(field, &QLineEdit::returnPressed, this, &StationEditor::commit);
        connect(field, &QLineEdit::textEdited, this, [this] {
            m_notSent.clear();
            showTyped();
        });
        field->installEventFilter(this);
    }
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_country);
    layout->addWidget(m_unit);
    layout->addStretch(1);
    refresh();
    connect(command, &CommandState::changed, this, &StationEditor::refresh);
}

std::optional<std::int64_t> StationEditor::countryCode(const QString& text)
{
    if (!text.isEmpty() && text.front().isDigit())
        return text.toInt();
    if (const auto dialling = rcm::diallingCodeForCountry(text.toStdString()))
        return *dialling;
    return std::nullopt;
}

void StationEditor::refresh()
{
    setEnabled(m_command->unit(m_ref) != nullptr);
    // Text the operator is typing, or typed and not commanded, stays.
    if (m_country->isModified() || m_unit->isModified())
        return;
    const rcm::Value* v = m_command->value(m_ref, m_id);
    QString country;
    QString unit;
    if (v) {
        const std::string_view alpha2 = rcm::countryForDiallingCode(static_cast<std::uint16_t>(v->number));
        country = alpha2.empty() ? QString::number(v->number) : QString::fromLatin1(alpha2.data(), 2);
        unit = QString::number(v->second);
    }
    if (m_country->text() != country)
        m_country->setText(country);
    if (m_unit->text() != unit)
        m_unit->setText(unit);
    setProblem(nullptr, {});
}

void StationEditor::setProblem(QLineEdit* field, const QString& reason)
{
    setProperty("incomplete", field != nullptr);
    setProperty("edited", false);
    for (QLineEdit* f : {m_country, m_unit}) {
        const bool atFault = f == field;
        f->setProperty("invalid", atFault);
        f->setStyleSheet(atFault ? DeliberateInput::invalidStyle("QLineEdit") : QString());
    }
    const QString notice = m_notSent.isEmpty() ? QString() : m_notSent + QLatin1Char('\n');
    m_country->setToolTip(notice + countryToolTip());
    m_unit->setToolTip(notice + unitToolTip());
    if (field)
        field->setToolTip(tr("%1. Not sent: the command keeps %2").arg(reason, commandedText()));
}

QString StationEditor::commandedText() const
{
    const rcm::Value* v = m_command->value(m_ref, m_id);
    return v ? ItemText::value(m_id, *v) : tr("no %1").arg(ItemText::label(m_id));
}

StationEditor::Typed StationEditor::typed() const
{
    const QString country = m_country->text().trimmed();
    const QString unit = m_unit->text().trimmed();
    if (country.isEmpty() && unit.isEmpty())
        return {};  // not sent
    if (country.isEmpty())
        return {std::nullopt, m_country, tr("No country for unit %1").arg(unit)};
    const auto code = countryCode(country);
    if (!code)
        return {std::nullopt, m_country,
                tr("%1 is not an ISO 3166 country with a dialling code").arg(country.toUpper())};
    if (unit.isEmpty())
        return {std::nullopt, m_unit, tr("No unit number for %1").arg(country.toUpper())};
    if (unit.toInt() > kUnitMax)
        return {std::nullopt, m_unit, tr("Unit %1 is above %2").arg(unit).arg(kUnitMax)};
    const rcm::Value value =
        rcm::Value::station({static_cast<std::uint16_t>(*code), static_cast<std::uint16_t>(unit.toInt())});
    if (const std::string reason = rcm::checkValue(rcm::itemInfo(m_id), value); !reason.empty())
        return {std::nullopt, m_country, QString::fromStdString(reason)};
    return {value, nullptr, {}};
}

bool StationEditor::eventFilter(QObject* watched, QEvent* event)
{
    if (event->type() == QEvent::FocusOut && (watched == m_country || watched == m_unit))
        fieldLeft(static_cast<QFocusEvent*>(event)->reason());
    return QWidget::eventFilter(watched, event);
}

QString StationEditor::typedText() const
{
    const QString country = m_country->text().trimmed().toUpper();
    const QString unit = m_unit->text().trimmed();
    return unit.isEmpty() ? country : country + QLatin1Char('_') + unit;
}

void StationEditor::fieldLeft(Qt::FocusReason reason)
{
    // A context menu over the text is still this field.
    if (reason == Qt::PopupFocusReason || CommandGate::of(m_command)->asking())
        return;
    if (!m_country->isModified() && !m_unit->isModified())
        return;
    // Country to unit or back is still typing the one station: shown, not sent.
    const QWidget* next = QApplication::focusWidget();
    if (reason == Qt::ActiveWindowFocusReason || (next != m_country && next != m_unit)) {
        restoreUnsent();
        return;
    }
    const Typed t = typed();
    if (t.atFault) {
        setProblem(t.atFault, t.problem);
        return;
    }
    showTyped();
}

void StationEditor::showTyped()
{
    const Typed t = typed();
    setProblem(nullptr, {});
    if (t.atFault)
        return;  // said when the operator moves on (Tab, Enter), not at every key
    const rcm::Value* v = m_command->value(m_ref, m_id);
    const bool differs = t.value ? !v || *v != *t.value : v != nullptr;
    setProperty("edited", differs);
    for (QLineEdit* f : {m_country, m_unit}) {
        f->setStyleSheet(differs ? DeliberateInput::editedStyle("QLineEdit") : QString());
        if (differs)
            f->setToolTip(tr("Not sent yet: Enter sends it; leaving the station goes back to the command (%1)")
                              .arg(commandedText()));
    }
}

void StationEditor::restoreUnsent()
{
    const Typed t = typed();
    const rcm::Value* v = m_command->value(m_ref, m_id);
    const bool differs = t.atFault || (t.value ? !v || *v != *t.value : v != nullptr);
    const QString left = typedText();
    m_country->setModified(false);
    m_unit->setModified(false);
    m_notSent =
        differs ? tr("Not sent: '%1' was left unsent; the command stays %2").arg(left, commandedText()) : QString();
    refresh();
    if (differs)
        CommandGate::of(m_command)->tellNotSent(m_ref, m_id, m_notSent);
}

void StationEditor::commit()
{
    const Typed t = typed();
    if (t.atFault) {
        setProblem(t.atFault, t.problem);
        return;
    }
    const bool done =
        t.value ? CommandGate::of(m_command)->setItem(this, m_ref, m_id, *t.value) : m_command->eraseItem(m_ref, m_id);
    if (!done)
        return;
    m_notSent.clear();
    m_country->setModified(false);
    m_unit->setModified(false);
    refresh();
}
