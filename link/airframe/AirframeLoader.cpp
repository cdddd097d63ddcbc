#include "link/airframe/AirframeLoader.h"

#include "codec/message/MessageEncoder.h"
#include "link/json/JsonPosition.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <set>
#include <utility>

// The resources live in this static library; a program linking it gets them
// only if something here names their initialiser.
static void initAirframeResources()
{
    static const bool done = [] {
        Q_INIT_RESOURCE(airframes);
        return true;
    }();
    Q_UNUSED(done);
}

const QString AirframeLoader::kDefaultPath = QStringLiteral(":/airframes/well-equipped.json");

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

// Members other than `allowed`: a typo would otherwise drop a unit unnoticed.
QString unknownMember(const QJsonObject& object, std::initializer_list<const char*> allowed)
{
    for (auto it = object.begin(); it != object.end(); ++it) {
        bool known = false;
        for (const char* name : allowed)
            known = known || it.key() == QLatin1String(name);
        if (!known)
            return it.key();
    }
    return {};
}

// `member` of `root`, when present: an array of objects with the members `allowed`.
std::optional<QString> readUnitList(const QJsonObject& root, const char* member,
                                    std::initializer_list<const char*> allowed, QJsonArray* out)
{
    const QJsonValue v = root.value(QLatin1String(member));
    if (v.isUndefined())
        return std::nullopt;
    if (!v.isArray())
        return QStringLiteral("\"%1\" must be an array").arg(QLatin1String(member));
    *out = v.toArray();
    for (qsizetype i = 0; i < out->size(); ++i) {
        if (!out->at(i).isObject())
            return QStringLiteral("%1[%2] must be an object").arg(QLatin1String(member)).arg(i);
        if (const QString key = unknownMember(out->at(i).toObject(), allowed); !key.isEmpty())
            return QStringLiteral("%1[%2]: unknown member \"%3\"").arg(QLatin1String(member)).arg(i).arg(key);
    }
    return std::nullopt;
}

QString memberText(const QJsonObject& o, const char* member)
{
    return o.value(QLatin1String(member)).toString();
}

bool isWholeByte(const QJsonValue& value)
{
    const double n = value.toDouble(-1);
    return value.isDouble() && n == double(int(n)) && n >= 0 && n <= 255;
}

std::optional<QString> readEngines(const QJsonArray& engines, rcm::Airframe& a)
{
    std::set<int> engineIds;
    for (qsizetype i = 0; i < engines.size(); ++i) {
        const QJsonObject o = engines[i].toObject();
        const QJsonValue id = o.value(QStringLiteral("id"));
        if (!isWholeByte(id))
            return QStringLiteral("engines[%1]: \"id\" must be a whole number 0..255").arg(i);
        const int n = id.toInt();
        if (!engineIds.insert(n).second)
            return QStringLiteral("engines[%1]: engine %2 is listed twice").arg(i).arg(n);
        a.engines.push_back({std::uint8_t(n), memberText(o, "name").toStdString()});
    }
    return std::nullopt;
}

std::optional<QString> readRadios(const QJsonArray& radios, rcm::Airframe& a)
{
    std::set<QString> radioIds;
    for (qsizetype i = 0; i < radios.size(); ++i) {
        const QJsonObject o = radios[i].toObject();
        const QString id = memberText(o, "systemId");
        if (!printableAscii(id, 1, 8) || id.endsWith(QLatin1Char(' ')))
            return QStringLiteral(
                       "radios[%1]: \"systemId\" must be 1 to 8 printable ASCII characters, "
                       "not ending in a space")
                .arg(i);
        if (!radioIds.insert(id).second)
            return QStringLiteral("radios[%1]: radio %2 is listed twice").arg(i).arg(id);
        a.radios.push_back({id.toStdString(), memberText(o, "name").toStdString()});
    }
    return std::nullopt;
}

std::optional<QString> readCameras(const QJsonArray& cameras, rcm::Airframe& a)
{
    std::set<std::pair<QString, int>> cameraIds;
    for (qsizetype i = 0; i < cameras.size(); ++i) {
        const QJsonObject o = cameras[i].toObject();
        const QString maker = memberText(o, "maker");
        const QJsonValue number = o.value(QStringLiteral("number"));
        if (!printableAscii(maker, 3, 3))
            return QStringLiteral("cameras[%1]: \"maker\" must be 3 printable ASCII characters").arg(i);
        if (!isWholeByte(number))
            return QStringLiteral("cameras[%1]: \"number\" must be a whole number 0..255").arg(i);
        const int n = number.toInt();
        if (!cameraIds.insert({maker, n}).second)
            return QStringLiteral("cameras[%1]: camera %2 %3 is listed twice").arg(i).arg(maker).arg(n);
        a.cameras.push_back({maker.toStdString(), std::uint8_t(n), memberText(o, "name").toStdString()});
    }
    return std::nullopt;
}

// The unit lists of an airframe object: engines, radios, cameras.
std::optional<QString> readUnits(const QJsonObject& root, rcm::Airframe& a)
{
    QJsonArray engines, radios, cameras;
    if (auto e = readUnitList(root, "engines", {"id", "name"}, &engines))
        return e;
    if (auto e = readUnitList(root, "radios", {"systemId", "name"}, &radios))
        return e;
    if (auto e = readUnitList(root, "cameras", {"maker", "number", "name"}, &cameras))
        return e;
    if (auto e = readEngines(engines, a))
        return e;
    if (auto e = readRadios(radios, a))
        return e;
    return readCameras(cameras, a);
}

}  // namespace

std::optional<rcm::Airframe> AirframeLoader::load(const QString& path, QString* error)
{
    initAirframeResources();
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        if (error)
            *error = QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(path), file.errorString());
        return std::nullopt;
    }
    return fromJson(file.readAll(), QDir::toNativeSeparators(path), error);
}

std::optional<rcm::Airframe> AirframeLoader::fromJson(const QByteArray& json, const QString& source, QString* error)
{
    const auto fail = [&](const QString& what) -> std::optional<rcm::Airframe> {
        if (error)
            *error = QStringLiteral("%1: %2").arg(source, what);
        return std::nullopt;
    };
    QJsonParseError parseError;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
    if (parseError.error != QJsonParseError::NoError)
        return fail(QStringLiteral("%1: %2").arg(jsonPosition(json, parseError.offset), parseError.errorString()));
    if (!doc.isObject())
        return fail(QStringLiteral("an airframe is a JSON object"));
    const QJsonObject root = doc.object();
    if (const QString key = unknownMember(root, {"name", "engines", "radios", "cameras", "senseAndAvoid"});
        !key.isEmpty())
        return fail(
            QStringLiteral("unknown member \"%1\" (known: name, engines, radios, cameras, senseAndAvoid)").arg(key));

    rcm::Airframe a;
    const QJsonValue name = root.value(QStringLiteral("name"));
    if (!name.isString() || name.toString().trimmed().isEmpty())
        return fail(QStringLiteral("\"name\" must be a non-empty string"));
    a.name = name.toString().toStdString();
    const QJsonValue sense = root.value(QStringLiteral("senseAndAvoid"));
    if (!sense.isUndefined() && !sense.isBool())
        return fail(QStringLiteral("\"senseAndAvoid\" must be true or false"));
    a.senseAndAvoid = sense.toBool(true);
    if (auto e = readUnits(root, a))
        return fail(*e);

    // The units must fit in one frame, resting command and all.
    const rcm::Diagnostics problems = rcm::validate(rcm::restingCommand(a));
    if (!problems.empty())
        return fail(QStringLiteral("these units do not fit in one message: %1")
                        .arg(QString::fromStdString(problems.front().toString())));
    return a;
}

QByteArray AirframeLoader::toJson(const rcm::Airframe& airframe)
{
    QJsonArray engines, radios, cameras;
    for (const rcm::EngineSpec& e : airframe.engines)
        engines.append(
            QJsonObject{{QStringLiteral("id"), int(e.id)}, {QStringLiteral("name"), QString::fromStdString(e.name)}});
    for (const rcm::RadioSpec& r : airframe.radios)
        radios.append(QJsonObject{{QStringLiteral("systemId"), QString::fromStdString(r.systemId)},
                                  {QStringLiteral("name"), QString::fromStdString(r.name)}});
    for (const rcm::CameraSpec& c : airframe.cameras)
        cameras.append(QJsonObject{{QStringLiteral("maker"), QString::fromStdString(c.maker)},
                                   {QStringLiteral("number"), int(c.number)},
                                   {QStringLiteral("name"), QString::fromStdString(c.name)}});
    const QJsonObject root{{QStringLiteral("name"), QString::fromStdString(airframe.name)},
                           {QStringLiteral("engines"), engines},
                           {QStringLiteral("radios"), radios},
                           {QStringLiteral("cameras"), cameras},
                           {QStringLiteral("senseAndAvoid"), airframe.senseAndAvoid}};
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

QStringList AirframeLoader::builtIn()
{
    initAirframeResources();
    QStringList paths;
    const QDir dir(QStringLiteral(":/airframes"));
    for (const QString& name : dir.entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name))
        paths << dir.filePath(name);
    return paths;
}
