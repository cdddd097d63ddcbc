#include "link/AirframeFile.h"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

using rcm::Airframe;

namespace {

bool printableAscii(const QString& s, qsizetype min, qsizetype max)
{
    if (s.size() < min || s.size() > max)
        return false;
    for (QChar c : s)
        if (c.unicode() < 0x20 || c.unicode() > 0x7E)
            return false;
    return true;
}

}  // namespace

std::optional<Airframe> parseAirframe(const QByteArray& json, const QString& source, QString* error)
{
    const auto fail = [&](const QString& what) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(source, what);
        return std::nullopt;
    };
    QJsonParseError parseError;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
    if (parseError.error != QJsonParseError::NoError)
        return fail(QStringLiteral("invalid JSON at byte offset %1: %2").arg(parseError.offset).arg(parseError.errorString()));
    if (!doc.isObject())
        return fail(QStringLiteral("the top level must be a JSON object"));
    const QJsonObject root = doc.object();

    Airframe a;
    a.name = root.value(QStringLiteral("name")).toString(QStringLiteral("Airframe")).toStdString();
    a.senseAndAvoid = root.value(QStringLiteral("senseAndAvoid")).toBool(true);
    const QJsonArray engines = root.value(QStringLiteral("engines")).toArray();
    for (qsizetype i = 0; i < engines.size(); ++i) {
        const QJsonObject e = engines[i].toObject();
        const int id = e.value(QStringLiteral("id")).toInt(-1);
        if (id < 0 || id > 255)
            return fail(QStringLiteral("engines[%1].id must be 0..255").arg(i));
        for (const rcm::EngineSpec& other : a.engines)
            if (other.id == id)
                return fail(QStringLiteral("engines[%1].id %2 is given twice").arg(i).arg(id));
        a.engines.push_back({static_cast<std::uint8_t>(id), e.value(QStringLiteral("name")).toString().toStdString()});
    }
    const QJsonArray radios = root.value(QStringLiteral("radios")).toArray();
    for (qsizetype i = 0; i < radios.size(); ++i) {
        const QJsonObject r = radios[i].toObject();
        const QString id = r.value(QStringLiteral("systemId")).toString();
        // Trailing spaces are the padding of system_ID on the wire.
        if (!printableAscii(id, 1, 8) || id.endsWith(QLatin1Char(' ')))
            return fail(QStringLiteral("radios[%1].systemId \"%2\" must be 1..8 printable ASCII characters, not "
                                       "ending in a space")
                            .arg(i)
                            .arg(id));
        a.radios.push_back({id.toStdString(), r.value(QStringLiteral("name")).toString().toStdString()});
    }
    const QJsonArray cameras = root.value(QStringLiteral("cameras")).toArray();
    for (qsizetype i = 0; i < cameras.size(); ++i) {
        const QJsonObject c = cameras[i].toObject();
        const QString maker = c.value(QStringLiteral("maker")).toString();
        const int number = c.value(QStringLiteral("number")).toInt(-1);
        if (!printableAscii(maker, 3, 3))
            return fail(QStringLiteral("cameras[%1].maker \"%2\" must be 3 printable ASCII characters").arg(i).arg(maker));
        if (number < 0 || number > 255)
            return fail(QStringLiteral("cameras[%1].number must be 0..255").arg(i));
        a.cameras.push_back({maker.toStdString(), static_cast<std::uint8_t>(number),
                             c.value(QStringLiteral("name")).toString().toStdString()});
    }
    return a;
}

std::optional<Airframe> loadAirframe(const QString& path, QString* error)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(path, file.errorString());
        return std::nullopt;
    }
    return parseAirframe(file.readAll(), path, error);
}

QByteArray airframeToJson(const Airframe& airframe)
{
    QJsonObject root;
    root.insert(QStringLiteral("name"), QString::fromStdString(airframe.name));
    root.insert(QStringLiteral("senseAndAvoid"), airframe.senseAndAvoid);
    QJsonArray engines, radios, cameras;
    for (const rcm::EngineSpec& e : airframe.engines)
        engines.append(QJsonObject{{QStringLiteral("id"), e.id}, {QStringLiteral("name"), QString::fromStdString(e.name)}});
    for (const rcm::RadioSpec& r : airframe.radios)
        radios.append(QJsonObject{{QStringLiteral("systemId"), QString::fromStdString(r.systemId)},
                                  {QStringLiteral("name"), QString::fromStdString(r.name)}});
    for (const rcm::CameraSpec& c : airframe.cameras)
        cameras.append(QJsonObject{{QStringLiteral("maker"), QString::fromStdString(c.maker)},
                                   {QStringLiteral("number"), c.number},
                                   {QStringLiteral("name"), QString::fromStdString(c.name)}});
    root.insert(QStringLiteral("engines"), engines);
    root.insert(QStringLiteral("radios"), radios);
    root.insert(QStringLiteral("cameras"), cameras);
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}
