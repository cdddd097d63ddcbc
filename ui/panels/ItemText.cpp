#include "ui/panels/ItemText.h"

#include "codec/message/CountryCodes.h"
#include "codec/message/DigitPairs.h"
#include "codec/message/ValueCodec.h"

namespace ItemText {
namespace {

QString fromView(std::string_view s)
{
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

QString withUnit(const rcm::ItemInfo& info, const QString& number)
{
    return info.unit.empty() ? number : number + QLatin1Char(' ') + fromView(info.unit);
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
        case rcm::ValueKind::Signed:
            range = withUnit(info, QString::fromStdString(rcm::formatScaled(info, info.min)) + QStringLiteral("..") +
                                       QString::fromStdString(rcm::formatScaled(info, info.max)));
            break;
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
        codes << fieldCodeName(id, field, code);
    return label(id, field) + QStringLiteral(" (") + label(id) + QStringLiteral("): ") +
           codes.join(QStringLiteral(", "));
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
            return withUnit(info, QString::fromStdString(rcm::formatScaled(info, v.number)));
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

QString fieldValue(rcm::ItemId id, int field, const rcm::Value& v)
{
    return fieldCodeName(id, field, rcm::fieldCode(static_cast<std::uint8_t>(v.number), field));
}

}  // namespace ItemText
