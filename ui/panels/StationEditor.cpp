#include "ui/panels/StationEditor.h"

#include "codec/message/CountryCodes.h"
#include "codec/message/ValueCodec.h"
#include "ui/panels/CommandState.h"
#include "ui/panels/ItemText.h"

#include <QHBoxLayout>
#include <QLineEdit>
#include <QRegularExpressionValidator>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QStyle>
#include <QStyleOptionFrame>

#include <algorithm>
#include <limits>

namespace {

const QString kInvalidStyle = QStringLiteral("QLineEdit { background-color: #ffbf00; color: black; }");

QString countryToolTip()
{
    return StationEditor::tr("ISO 3166 alpha-2 (GB) or dialling code (44); empty: not sent");
}

// Wide enough for the widest entry the validator lets through ("WW", four
// digits such as 1929) and for the placeholder, with the frame and margins the
// style gives a line edit: a fixed guess in pixels cut the placeholder off.
int countryFieldWidth(const QLineEdit* edit)
{
    const QFontMetrics metrics = edit->fontMetrics();
    int text = 0;
    for (const QString& sample : {QStringLiteral("WW"), QStringLiteral("0000"), edit->placeholderText()})
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
      m_unit(new QSpinBox(this))
{
    setObjectName(ItemText::name(id));
    setAccessibleName(ItemText::label(id));
    setToolTip(ItemText::toolTip(id));
    m_country->setObjectName(QStringLiteral("country"));
    // Empty means the item is not sent, which is what the placeholder says;
    // the tooltip says what to type.
    m_country->setPlaceholderText(tr("none"));
    m_country->setToolTip(countryToolTip());
    m_country->setValidator(
        new QRegularExpressionValidator(QRegularExpression(QStringLiteral("[A-Za-z]{0,2}|[0-9]{0,4}")), m_country));
    m_country->setMaxLength(4);
    m_country->setFixedWidth(countryFieldWidth(m_country));
    m_unit->setObjectName(QStringLiteral("unit"));
    m_unit->setRange(0, std::numeric_limits<std::uint16_t>::max());
    m_unit->setKeyboardTracking(false);
    m_unit->setToolTip(tr("Unit number, 0..65535"));
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_country);
    layout->addWidget(m_unit, 1);
    refresh();
    connect(m_country, &QLineEdit::editingFinished, this, &StationEditor::commit);
    connect(m_country, &QLineEdit::textEdited, this, [this] { setInvalid({}); });
    connect(m_unit, &QSpinBox::valueChanged, this, &StationEditor::commit);
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
    const rcm::Value* v = m_command->value(m_ref, m_id);
    // Text the operator is typing, or typed and the command refused, stays.
    if (!m_country->isModified()) {
        QString country;
        if (v) {
            const std::string_view alpha2 = rcm::countryForDiallingCode(static_cast<std::uint16_t>(v->number));
            country = alpha2.empty() ? QString::number(v->number) : QString::fromLatin1(alpha2.data(), 2);
        }
        if (m_country->text() != country)
            m_country->setText(country);
    }
    if (v && v->second != m_unit->value()) {
        const QSignalBlocker block(m_unit);
        m_unit->setValue(static_cast<int>(v->second));
    }
}

void StationEditor::setInvalid(const QString& reason)
{
    m_country->setProperty("invalid", !reason.isEmpty());
    m_country->setStyleSheet(reason.isEmpty() ? QString() : kInvalidStyle);
    m_country->setToolTip(reason.isEmpty() ? countryToolTip() : reason);
}

void StationEditor::commit()
{
    const QString text = m_country->text().trimmed();
    if (text.isEmpty()) {
        setInvalid({});
        if (m_command->eraseItem(m_ref, m_id))
            m_country->setModified(false);
        return;
    }
    const auto code = countryCode(text);
    if (!code) {
        setInvalid(tr("%1 is not an ISO 3166 country with a dialling code").arg(text.toUpper()));
        return;
    }
    const rcm::Value value =
        rcm::Value::station({static_cast<std::uint16_t>(*code), static_cast<std::uint16_t>(m_unit->value())});
    if (const std::string reason = rcm::checkValue(rcm::itemInfo(m_id), value); !reason.empty()) {
        setInvalid(QString::fromStdString(reason));
        return;
    }
    setInvalid({});
    if (m_command->setItem(m_ref, m_id, value)) {
        m_country->setModified(false);
        refresh();
    }
}
