#include "ui/panels/ItemText.h"

#include "codec/message/CountryCodes.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/ValueCodec.h"

#include <QCoreApplication>
#include <QRegularExpression>

#include <algorithm>

namespace ItemText {
namespace {

QString fromView(std::string_view s)
{
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

// a / b rounded to the nearest, halves away from zero; b > 0.
std::int64_t roundedQuotient(std::int64_t a, std::int64_t b)
{
    return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b);
}

std::int64_t powerOfTen(int decimals)
{
    std::int64_t p = 1;
    while (decimals-- > 0)
        p *= 10;
    return p;
}

QString station(const rcm::Value& v)
{
    const std::string_view alpha2 = rcm::countryForDiallingCode(static_cast<std::uint16_t>(v.number));
    const QString country = alpha2.empty() ? QString::number(v.number) : fromView(alpha2);
    return country + QLatin1Char('_') + QString::number(v.second);
}

}  // namespace

QString name(rcm::ItemId id, int field)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    if (field < 0)
        return fromView(info.name);
    return fromView(info.name) + QLatin1Char('.') + fromView(info.fields[static_cast<std::size_t>(field)].name);
}

QString label(rcm::ItemId id, int field)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    return field < 0 ? fromView(info.label) : fromView(info.fields[static_cast<std::size_t>(field)].label);
}

QString toolTip(rcm::ItemId id)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    QString range;
    switch (info.kind) {
        case rcm::ValueKind::Unsigned:
        case rcm::ValueKind::Signed: {
            const rcm::Presentation shown = rcm::presentation(info);
            range = number(id, shown.min) + QStringLiteral("..") + number(id, shown.max) + unitSuffix(id);
        } break;
        case rcm::ValueKind::Station:
            range = QStringLiteral("country as ISO alpha-2 or dialling code %1..%2, unit 0..65535")
                        .arg(info.min)
                        .arg(info.max);
            break;
        case rcm::ValueKind::Text:
            range = QStringLiteral("up to %1 characters").arg(info.size);
            break;
        default:
            break;
    }
    return range.isEmpty() ? label(id) : label(id) + QStringLiteral(", ") + range;
}

QString fieldToolTip(rcm::ItemId id, int field)
{
    QStringList codes;
    for (unsigned code : validFieldCodes(id, field))
        codes << fieldCodeWord(id, field, code);
    return label(id, field) + QStringLiteral(" (") + label(id) + QStringLiteral("): ") +
           codes.join(QStringLiteral(", "));
}

QString number(rcm::ItemId id, std::int64_t wire)
{
    const rcm::Presentation shown = rcm::presentation(rcm::itemInfo(id));
    const std::int64_t unit = powerOfTen(shown.decimals);
    const std::int64_t scaled = roundedQuotient(wire * shown.shown * unit, shown.wire);
    const std::int64_t magnitude = scaled < 0 ? -scaled : scaled;
    QString text = QString::number(magnitude / unit);
    if (shown.decimals > 0)
        text += QLatin1Char('.') + QString::number(magnitude % unit).rightJustified(shown.decimals, QLatin1Char('0'));
    return scaled < 0 ? QLatin1Char('-') + text : text;
}

QString unitSuffix(rcm::ItemId id)
{
    const rcm::Presentation shown = rcm::presentation(rcm::itemInfo(id));
    if (shown.unit.empty())
        return {};
    const QString unit = fromView(shown.unit);
    return unit == QStringLiteral("\u00b0") ? unit : QLatin1Char(' ') + unit;
}

std::optional<std::int64_t> parseNumber(rcm::ItemId id, QString text)
{
    const rcm::Presentation shown = rcm::presentation(rcm::itemInfo(id));
    text = text.trimmed();
    const QString suffix = unitSuffix(id).trimmed();
    if (!suffix.isEmpty() && text.endsWith(suffix))
        text = text.chopped(suffix.size()).trimmed();
    static const QRegularExpression kNumber(QStringLiteral("^([-+]?)([0-9]+)(?:\\.([0-9]*))?$"));
    const QRegularExpressionMatch m = kNumber.match(text);
    if (!m.hasMatch() || m.captured(3).size() > shown.decimals || m.captured(2).size() > 12)
        return std::nullopt;
    const std::int64_t unit = powerOfTen(shown.decimals);
    const QString fraction = m.captured(3).leftJustified(shown.decimals, QLatin1Char('0'));
    std::int64_t scaled = m.captured(2).toLongLong() * unit + (fraction.isEmpty() ? 0 : fraction.toLongLong());
    if (m.captured(1) == QStringLiteral("-"))
        scaled = -scaled;
    // Outside the range as shown (100.1 %), even where it would round into it.
    const auto shownScaled = [&](std::int64_t wire) { return roundedQuotient(wire * shown.shown * unit, shown.wire); };
    if (scaled < shownScaled(shown.min) || scaled > shownScaled(shown.max))
        return std::nullopt;
    return std::clamp(roundedQuotient(scaled * shown.wire, shown.shown * unit), shown.min, shown.max);
}

QString fieldCodeWord(rcm::ItemId id, int field, unsigned code)
{
    const rcm::FieldInfo& info = rcm::itemInfo(id).fields[static_cast<std::size_t>(field)];
    if (rcm::fieldCodeValid(info, code) && !info.words[code & 3u].empty())
        return fromView(info.words[code & 3u]);
    return fieldCodeName(id, field, code);
}

QString fieldCodeWord(rcm::ItemId id, int field, unsigned code, const rcm::Unit* unit)
{
    // eng_status MASTER_SLAVE: "master eng 1 + slave eng 3" (PROFILE.md), by eng_ID.
    constexpr std::int64_t kMasterEngine = 1;
    constexpr std::int64_t kSlaveEngine = 3;
    if (id == rcm::ItemId::eng_status && field == 1 && code == rcm::code::kMasterSlave && unit) {
        const rcm::Value* key = unit->find(rcm::ItemId::eng_ID);
        if (key && key->number == kMasterEngine)
            return QCoreApplication::translate("ItemText", "Master of engine %1").arg(kSlaveEngine);
        if (key && key->number == kSlaveEngine)
            return QCoreApplication::translate("ItemText", "Slave of engine %1").arg(kMasterEngine);
    }
    return fieldCodeWord(id, field, code);
}

QString fieldCodeName(rcm::ItemId id, int field, unsigned code)
{
    const rcm::FieldInfo& info = rcm::itemInfo(id).fields[static_cast<std::size_t>(field)];
    if (rcm::fieldCodeValid(info, code))
        return fromView(info.codes[code & 3u]);
    return QStringLiteral("corrupt (%1%2)").arg(code >> 1 & 1u).arg(code & 1u);
}

QList<unsigned> validFieldCodes(rcm::ItemId id, int field)
{
    const rcm::FieldInfo& info = rcm::itemInfo(id).fields[static_cast<std::size_t>(field)];
    QList<unsigned> codes;
    for (unsigned code = 0; code < 4; ++code)
        if (rcm::fieldCodeValid(info, code))
            codes << code;
    return codes;
}

QString value(rcm::ItemId id, const rcm::Value& v)
{
    const rcm::ItemInfo& info = rcm::itemInfo(id);
    switch (info.kind) {
        case rcm::ValueKind::Unsigned:
        case rcm::ValueKind::Signed:
            return number(id, v.number) + unitSuffix(id);
        case rcm::ValueKind::Station:
            return station(v);
        case rcm::ValueKind::Time: {
            const rcm::DigitPairs time = rcm::DigitPairs::unpack(v.number);
            return QStringLiteral("%1:%2:%3")
                .arg(time.high, 2, 10, QLatin1Char('0'))
                .arg(time.middle, 2, 10, QLatin1Char('0'))
                .arg(time.low, 2, 10, QLatin1Char('0'));
        }
        case rcm::ValueKind::Date:
            return QStringLiteral("%1").arg(v.number, 6, 10, QLatin1Char('0'));
        case rcm::ValueKind::BytePair:
            return QStringLiteral("%1 %2").arg(v.number).arg(v.second);
        case rcm::ValueKind::Fields: {
            QStringList parts;
            for (int f = 0; f < static_cast<int>(info.fields.size()); ++f)
                parts << fromView(info.fields[static_cast<std::size_t>(f)].name) + QLatin1Char('=') +
                             fieldValue(id, f, v);
            return parts.join(QLatin1Char(' '));
        }
        case rcm::ValueKind::Text:
            return QString::fromStdString(v.text);
        case rcm::ValueKind::CameraId:
            return QString::fromStdString(v.text) + QLatin1Char(' ') + QString::number(v.number);
        case rcm::ValueKind::Raw:
            return QStringLiteral("0x") + QString::number(v.number, 16).toUpper().rightJustified(2, QLatin1Char('0'));
    }
    return {};
}

QString fieldValue(rcm::ItemId id, int field, const rcm::Value& v, const rcm::Unit* unit)
{
    return fieldCodeWord(id, field, rcm::fieldCode(static_cast<std::uint8_t>(v.number), field), unit);
}

QString unitName(rcm::UnitKind kind, const std::optional<rcm::Value>& key)
{
    const QString label = fromView(rcm::unitLabel(kind));
    const std::optional<rcm::ItemId> keyItem = rcm::unitKey(kind);
    if (!keyItem || !key)
        return label;
    return label + QLatin1Char(' ') + value(*keyItem, *key).trimmed();
}

QString unitName(const rcm::Unit& unit)
{
    const std::optional<rcm::ItemId> key = rcm::unitKey(unit.kind());
    const rcm::Value* v = key ? unit.find(*key) : nullptr;
    return unitName(unit.kind(), v ? std::optional(*v) : std::nullopt);
}

QString unitNames(const std::vector<rcm::Unit>& units)
{
    QStringList names;
    for (const rcm::Unit& unit : units)
        names << unitName(unit);
    return names.join(QStringLiteral(", "));
}

QString changeWhere(const rcm::ItemChange& c)
{
    // A Fields item with one field says the field alone ("Nose wheel"); a
    // field of a unit's status item says both ("Engine status, Control source").
    const rcm::ItemInfo& info = rcm::itemInfo(c.id);
    QString item = label(c.id);
    if (c.field >= 0)
        item = info.fields.size() == 1 ? label(c.id, c.field) : item + QStringLiteral(", ") + label(c.id, c.field);
    return unitName(c.kind, c.key) + QStringLiteral(", ") + item;
}

QString changeValue(const rcm::ItemChange& c, const std::optional<rcm::Value>& side)
{
    if (!side)
        return QCoreApplication::translate("ItemText", "nothing");
    return c.field >= 0 ? fieldValue(c.id, c.field, *side) : value(c.id, *side);
}

QString change(const rcm::ItemChange& c)
{
    return changeWhere(c) + QStringLiteral(": ") + changeValue(c, c.from) + QStringLiteral(" -> ") +
           changeValue(c, c.to);
}

}  // namespace ItemText
