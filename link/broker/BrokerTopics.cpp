#include "link/broker/BrokerTopics.h"

#include "codec/message/CountryCodes.h"
#include "link/framelog/FrameLog.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonParseError>
#include <QStringList>

#include <array>
#include <limits>
#include <utility>

namespace {

const QString kRoot = QStringLiteral("rcm");

constexpr std::array<std::pair<LinkState, const char*>, 4> kLinkStates{{
    {LinkState::Closed, "closed"},
    {LinkState::Waiting, "waiting"},
    {LinkState::Connected, "connected"},
    {LinkState::Lost, "lost"},
}};
constexpr std::array<std::pair<FrameDirection, const char*>, 2> kFrameDirections{{
    {FrameDirection::Sent, "up"},
    {FrameDirection::Received, "down"},
}};
constexpr std::array<const char*, 4> kRoles{"control", "backup", "observing", "unknown"};
constexpr std::array<const char*, 4> kSeverities{"info", "warning", "error", "alarm"};

template <typename E, std::size_t N>
QString nameIn(const std::array<std::pair<E, const char*>, N>& table, E value)
{
    for (const auto& [v, name] : table)
        if (v == value)
            return QString::fromLatin1(name);
    return {};
}

template <typename E, std::size_t N>
std::optional<E> valueIn(const std::array<std::pair<E, const char*>, N>& table, const QString& name)
{
    for (const auto& [v, n] : table)
        if (name == QLatin1String(n))
            return v;
    return std::nullopt;
}

template <std::size_t N>
bool isOneOf(const std::array<const char*, N>& names, const QString& name)
{
    for (const char* n : names)
        if (name == QLatin1String(n))
            return true;
    return false;
}

// "\"a\", \"b\" or \"c\"", for an error that lists what a field may hold.
template <std::size_t N>
QString alternatives(const std::array<const char*, N>& names)
{
    QString out;
    for (std::size_t i = 0; i < N; ++i) {
        if (i > 0)
            out += i + 1 == N ? QStringLiteral(" or ") : QStringLiteral(", ");
        out += u'"' + QString::fromLatin1(names[i]) + u'"';
    }
    return out;
}

template <typename E, std::size_t N>
QString alternatives(const std::array<std::pair<E, const char*>, N>& table)
{
    std::array<const char*, N> names{};
    for (std::size_t i = 0; i < N; ++i)
        names[i] = table[i].second;
    return alternatives(names);
}

// The frame log's names of statuses and transports (FrameLog.h), the one
// spelling of them in the project, as a table like the ones above.
template <typename E, std::size_t N>
std::array<std::pair<E, const char*>, N> namedBy(QString (*name)(E))
{
    static std::array<QByteArray, N> texts;
    std::array<std::pair<E, const char*>, N> table{};
    for (std::size_t i = 0; i < N; ++i) {
        texts[i] = name(E(i)).toLatin1();
        table[i] = {E(i), texts[i].constData()};
    }
    return table;
}

const std::array<std::pair<FrameStatus, const char*>, 5> kFrameStatuses = namedBy<FrameStatus, 5>(&::frameStatusName);
const std::array<std::pair<FrameTransport, const char*>, 4> kFrameTransports =
    namedBy<FrameTransport, 4>(&::frameTransportName);

// Reads one payload's object, field by field, keeping the first error: each
// getter returns a default once something failed, and ok() says whether the
// whole payload held. Errors are "<payload>: <field> <what is wrong>".
class JsonFields {
public:
    JsonFields(const QByteArray& json, const char* payload) : m_payload(QString::fromLatin1(payload))
    {
        QJsonParseError parseError;
        const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
        if (parseError.error != QJsonParseError::NoError)
            m_error = m_payload +
                      QStringLiteral(": not JSON: %1 at byte %2").arg(parseError.errorString()).arg(parseError.offset);
        else if (!doc.isObject())
            m_error = m_payload + QStringLiteral(": not a JSON object");
        else
            m_object = doc.object();
    }

    bool ok() const { return m_error.isEmpty(); }
    // Passes the first error on; false when there was one.
    bool report(QString* error) const
    {
        if (error && !ok())
            *error = m_error;
        return ok();
    }
    bool has(const char* field) const { return ok() && m_object.contains(QLatin1String(field)); }

    // Absent (and not required) or wrong, the field reads as its type's
    // default: "", false, 0, [].
    QString string(const char* field, bool required = true)
    {
        return typed(field, required, &QJsonValue::isString, "must be a string").toString();
    }
    bool boolean(const char* field, bool required = true)
    {
        return typed(field, required, &QJsonValue::isBool, "must be true or false").toBool();
    }
    QJsonArray array(const char* field, bool required = true)
    {
        return typed(field, required, &QJsonValue::isArray, "must be an array").toArray();
    }

    // An integer in [min, max]. JSON numbers are doubles to most readers;
    // times in microseconds and counters stay well inside 2^53.
    qint64 integer(const char* field, qint64 min, qint64 max, bool required = true)
    {
        const QJsonValue v = typed(field, required, &QJsonValue::isDouble, "must be a number");
        if (v.isUndefined())
            return 0;
        const double d = v.toDouble();
        const qint64 n = v.toInteger(std::numeric_limits<qint64>::min());
        if (n == std::numeric_limits<qint64>::min() || double(n) != d) {
            fail(field, QStringLiteral("must be a whole number, not %1").arg(d));
            return 0;
        }
        if (n < min || n > max) {
            fail(field, QStringLiteral("must be %1..%2, not %3").arg(min).arg(max).arg(n));
            return 0;
        }
        return n;
    }
    qint64 time(const char* field, bool required = true)
    {
        return integer(field, 0, std::numeric_limits<qint64>::max(), required);
    }
    quint64 count(const char* field) { return quint64(integer(field, 0, std::numeric_limits<qint64>::max())); }

    template <std::size_t N>
    QString oneOf(const char* field, const std::array<const char*, N>& names)
    {
        const QString s = string(field);
        if (ok() && !isOneOf(names, s))
            fail(field, QStringLiteral("must be %1, not \"%2\"").arg(alternatives(names), s));
        return ok() ? s : QString();
    }

    template <typename E, std::size_t N>
    E named(const char* field, const std::array<std::pair<E, const char*>, N>& table, E fallback, bool required = true)
    {
        if (!required && !has(field))
            return fallback;
        const QString s = string(field);
        if (!ok())
            return fallback;
        const std::optional<E> v = valueIn(table, s);
        if (!v) {
            fail(field, QStringLiteral("must be %1, not \"%2\"").arg(alternatives(table), s));
            return fallback;
        }
        return *v;
    }

    QByteArray base64(const char* field)
    {
        const QString s = string(field);
        if (!ok())
            return {};
        auto decoded = QByteArray::fromBase64Encoding(s.toLatin1(), QByteArray::AbortOnBase64DecodingErrors);
        if (!decoded || s.size() % 4 != 0) {
            fail(field, QStringLiteral("must be base64"));
            return {};
        }
        return *decoded;
    }

    void fail(const char* field, const QString& what)
    {
        if (ok())
            m_error = m_payload + QStringLiteral(": ") + QLatin1String(field) + u' ' + what;
    }

private:
    // The field's value if isKind() holds for it; else Undefined, the error
    // "<field> <mustBe>" kept.
    QJsonValue typed(const char* field, bool required, bool (QJsonValue::*isKind)() const, const char* mustBe)
    {
        const QJsonValue v = value(field, required);
        if (v.isUndefined() || (v.*isKind)())
            return v;
        fail(field, QString::fromLatin1(mustBe));
        return QJsonValue(QJsonValue::Undefined);
    }

    // Undefined when absent (an error if required) or after an error.
    QJsonValue value(const char* field, bool required)
    {
        if (!ok())
            return QJsonValue(QJsonValue::Undefined);
        const QJsonValue v = m_object.value(QLatin1String(field));
        if (v.isUndefined() && required)
            fail(field, QStringLiteral("is missing"));
        return v;
    }

    QString m_payload;
    QJsonObject m_object;
    QString m_error;
};

QByteArray compact(const QJsonObject& object)
{
    return QJsonDocument(object).toJson(QJsonDocument::Compact);
}

// The reports whose fields are plain (all but FrameReport) list them once,
// in a fields() below, to a visitor: a JsonWriter for toJson(), a JsonReader
// for fromJson(). A field is written under its name whatever it holds; the
// reader reads in the list's order, so the error told is the first field's.
class JsonWriter {
public:
    void string(const char* field, const QString& value, bool /*required*/ = true) { put(field, value); }
    void boolean(const char* field, bool value) { put(field, value); }
    void time(const char* field, qint64 value, bool /*required*/ = true) { put(field, value); }
    void count(const char* field, quint64 value) { put(field, qint64(value)); }
    template <std::size_t N>
    void oneOf(const char* field, const QString& value, const std::array<const char*, N>& /*names*/)
    {
        put(field, value);
    }
    template <typename E, std::size_t N>
    void named(const char* field, E value, const std::array<std::pair<E, const char*>, N>& table, E /*fallback*/)
    {
        put(field, nameIn(table, value));
    }

    QByteArray json() const { return compact(m_object); }

private:
    void put(const char* field, const QJsonValue& value) { m_object.insert(QLatin1String(field), value); }

    QJsonObject m_object;
};

class JsonReader {
public:
    explicit JsonReader(JsonFields& fields) : m_fields(fields) {}

    void string(const char* field, QString& to, bool required = true) { to = m_fields.string(field, required); }
    void boolean(const char* field, bool& to) { to = m_fields.boolean(field); }
    void time(const char* field, qint64& to, bool required = true) { to = m_fields.time(field, required); }
    void count(const char* field, quint64& to) { to = m_fields.count(field); }
    template <std::size_t N>
    void oneOf(const char* field, QString& to, const std::array<const char*, N>& names)
    {
        to = m_fields.oneOf(field, names);
    }
    template <typename E, std::size_t N>
    void named(const char* field, E& to, const std::array<std::pair<E, const char*>, N>& table, E fallback)
    {
        to = m_fields.named(field, table, fallback);
    }

private:
    JsonFields& m_fields;
};

template <typename Report, typename Fields>
QByteArray writeJson(const Report& report, const Fields& fields)
{
    JsonWriter writer;
    fields(writer, report);
    return writer.json();
}

template <typename Report, typename Fields>
std::optional<Report> readJson(const QByteArray& json, const char* payload, QString* error, const Fields& fields)
{
    JsonFields f(json, payload);
    JsonReader reader(f);
    Report report;
    fields(reader, report);
    if (!f.report(error))
        return std::nullopt;
    return report;
}

// The stations the aircraft last named, in control and as backup: in both
// the station and the state reports.
constexpr auto kControlStationFields = [](auto& v, auto& r) {
    v.string("destination", r.destination, false);
    v.string("backup", r.backup, false);
};

}  // namespace

// StationReport ---------------------------------------------------------------

constexpr auto kStationFields = [](auto& v, auto& r) {
    v.string("station", r.station);
    v.oneOf("role", r.role, kRoles);
    v.named("link", r.link, kLinkStates, LinkState::Closed);
    v.string("description", r.description, false);
    v.boolean("online", r.online);
    v.time("utcMicros", r.utcMicros);
    v.time("lastFrameUtcMicros", r.lastFrameUtcMicros, false);
    kControlStationFields(v, r);
};

QByteArray StationReport::toJson() const
{
    return writeJson(*this, kStationFields);
}

std::optional<StationReport> StationReport::fromJson(const QByteArray& json, QString* error)
{
    return readJson<StationReport>(json, "station", error, kStationFields);
}

// FrameReport -----------------------------------------------------------------

QByteArray FrameReport::toJson() const
{
    QJsonObject o{
        {QStringLiteral("station"), station},
        {QStringLiteral("direction"), BrokerTopics::frameDirectionName(direction)},
        {QStringLiteral("status"), BrokerTopics::frameStatusName(status)},
        {QStringLiteral("utcMicros"), utcMicros},
        {QStringLiteral("bytes"), QString::fromLatin1(bytes.toBase64())},
        {QStringLiteral("transport"), BrokerTopics::frameTransportName(transport)},
    };
    if (messageId)
        o.insert(QStringLiteral("messageId"), qint64(*messageId));
    if (!corrected.isEmpty()) {
        QJsonArray a;
        for (int n : corrected)
            a.append(n);
        o.insert(QStringLiteral("corrected"), a);
    }
    if (!text.isEmpty())
        o.insert(QStringLiteral("text"), text);
    if (enciphered)
        o.insert(QStringLiteral("enciphered"), true);
    if (session)
        o.insert(QStringLiteral("session"), session);
    if (seq)
        o.insert(QStringLiteral("seq"), qint64(seq));
    return compact(o);
}

std::optional<FrameReport> FrameReport::fromJson(const QByteArray& json, QString* error)
{
    JsonFields f(json, "frames");
    FrameReport r;
    r.station = f.string("station");
    r.direction = f.named("direction", kFrameDirections, FrameDirection::Received);
    r.status = f.named("status", kFrameStatuses, FrameStatus::NotChecked);
    r.utcMicros = f.time("utcMicros");
    if (f.has("messageId"))
        r.messageId = quint32(f.integer("messageId", 0, std::numeric_limits<quint32>::max()));
    const QJsonArray corrected = f.array("corrected", false);
    for (const QJsonValue& v : corrected) {
        // One count per codeword: 0..16 bytes corrected (RS(255,223) corrects
        // up to 16), -1 beyond correction.
        if (!v.isDouble() || v.toDouble() != double(v.toInt()) || v.toInt() < -1 || v.toInt() > 255) {
            f.fail("corrected", QStringLiteral("must hold whole numbers -1..255"));
            break;
        }
        r.corrected.append(v.toInt());
    }
    r.bytes = f.base64("bytes");
    r.text = f.string("text", false);
    r.transport = f.named("transport", kFrameTransports, FrameTransport::Serial, false);
    r.enciphered = f.boolean("enciphered", false);
    r.session = f.time("session", false);
    r.seq = quint64(f.integer("seq", 0, std::numeric_limits<qint64>::max(), false));
    if (!f.report(error))
        return std::nullopt;
    return r;
}

// StateReport -----------------------------------------------------------------

constexpr auto kStateFields = [](auto& v, auto& r) {
    v.time("utcMicros", r.utcMicros);
    v.string("text", r.text);
    kControlStationFields(v, r);
};

QByteArray StateReport::toJson() const
{
    return writeJson(*this, kStateFields);
}

std::optional<StateReport> StateReport::fromJson(const QByteArray& json, QString* error)
{
    return readJson<StateReport>(json, "state", error, kStateFields);
}

// StatsReport -----------------------------------------------------------------

StatsReport StatsReport::of(const LinkStatistics& s)
{
    StatsReport r;
    r.framesSent = s.framesSent;
    r.framesReceived = s.framesReceived;
    r.refused = s.refusedTotal();
    r.correctedBytesBlock1 = s.correctedBytesBlock1;
    r.correctedBytesBlock2 = s.correctedBytesBlock2;
    r.lastGoodFrameUtcMicros = s.lastGoodFrameUtcMicros;
    r.state = s.state;
    return r;
}

LinkStatistics StatsReport::toStatistics() const
{
    LinkStatistics s;
    s.state = state;
    s.framesSent = framesSent;
    s.framesReceived = framesReceived;
    // The report keeps only the total; it is told as the first reason, so
    // refusedTotal() reads it back.
    s.refused[0] = refused;
    s.correctedBytesBlock1 = correctedBytesBlock1;
    s.correctedBytesBlock2 = correctedBytesBlock2;
    s.lastGoodFrameUtcMicros = lastGoodFrameUtcMicros;
    return s;
}

constexpr auto kStatsFields = [](auto& v, auto& r) {
    v.count("framesSent", r.framesSent);
    v.count("framesReceived", r.framesReceived);
    v.count("refused", r.refused);
    v.count("correctedBytesBlock1", r.correctedBytesBlock1);
    v.count("correctedBytesBlock2", r.correctedBytesBlock2);
    v.time("lastGoodFrameUtcMicros", r.lastGoodFrameUtcMicros);
    v.named("state", r.state, kLinkStates, LinkState::Closed);
};

QByteArray StatsReport::toJson() const
{
    return writeJson(*this, kStatsFields);
}

std::optional<StatsReport> StatsReport::fromJson(const QByteArray& json, QString* error)
{
    return readJson<StatsReport>(json, "stats", error, kStatsFields);
}

// EventReport -----------------------------------------------------------------

constexpr auto kEventFields = [](auto& v, auto& r) {
    v.time("utcMicros", r.utcMicros);
    v.oneOf("severity", r.severity, kSeverities);
    v.string("text", r.text);
    v.string("station", r.station, false);
};

QByteArray EventReport::toJson() const
{
    return writeJson(*this, kEventFields);
}

std::optional<EventReport> EventReport::fromJson(const QByteArray& json, QString* error)
{
    return readJson<EventReport>(json, "events", error, kEventFields);
}

// Topics ----------------------------------------------------------------------

namespace BrokerTopics {

namespace {

constexpr std::array<std::pair<Kind, const char*>, 5> kKinds{{
    {Kind::Station, "station"},
    {Kind::Frames, "frames"},
    {Kind::State, "state"},
    {Kind::Stats, "stats"},
    {Kind::Events, "events"},
}};

}  // namespace

qsizetype maxPayloadBytes(Kind kind)
{
    switch (kind) {
        case Kind::Station:
        case Kind::Stats:
            return 4 * 1024;
        case Kind::Events:
            return 8 * 1024;
        case Kind::Frames:
        case Kind::State:
            break;
    }
    return 16 * 1024;
}

QString kindName(Kind kind)
{
    return nameIn(kKinds, kind);
}

QString topic(const QString& aircraft, Kind kind, const QString& station)
{
    return kRoot + u'/' + aircraft + u'/' + kindName(kind) + u'/' + station;
}
QString stationTopic(const QString& aircraft, const QString& station)
{
    return topic(aircraft, Kind::Station, station);
}
QString framesTopic(const QString& aircraft, const QString& station)
{
    return topic(aircraft, Kind::Frames, station);
}
QString stateTopic(const QString& aircraft, const QString& station)
{
    return topic(aircraft, Kind::State, station);
}
QString statsTopic(const QString& aircraft, const QString& station)
{
    return topic(aircraft, Kind::Stats, station);
}
QString eventsTopic(const QString& aircraft, const QString& station)
{
    return topic(aircraft, Kind::Events, station);
}

QString allStationsPattern()
{
    return allPattern(Kind::Station);
}
QString allPattern(Kind kind)
{
    return kRoot + QStringLiteral("/+/") + kindName(kind) + QStringLiteral("/+");
}
QString aircraftPattern(const QString& aircraft)
{
    return kRoot + u'/' + aircraft + QStringLiteral("/#");
}

std::optional<Topic> parseTopic(const QString& topic)
{
    const QStringList levels = topic.split(u'/');
    if (levels.size() != 4 || levels[0] != kRoot || !isTopicLevel(levels[1]) || !isTopicLevel(levels[3]))
        return std::nullopt;
    const std::optional<Kind> kind = valueIn(kKinds, levels[2]);
    if (!kind)
        return std::nullopt;
    return Topic{levels[1], *kind, levels[3]};
}

bool isTopicLevel(const QString& name)
{
    if (name.isEmpty())
        return false;
    for (const QChar c : name)
        if (c == u'/' || c == u'+' || c == u'#' || c == QChar(0))
            return false;
    return true;
}

QString stationText(const rcm::Message& message, rcm::ItemId item)
{
    const rcm::Value* v = message.header.find(item);
    if (!v)
        return {};
    // As the text format prints a station (its appendStation): the country's
    // alpha-2 when the dialling code has one, else the number.
    std::string_view country;
    if (v->number >= 0 && v->number <= std::numeric_limits<quint16>::max())
        country = rcm::countryForDiallingCode(quint16(v->number));
    const QString countryText =
        country.empty() ? QString::number(v->number) : QString::fromLatin1(country.data(), qsizetype(country.size()));
    return countryText + u'_' + QString::number(v->second);
}

// Each enumeration's words in JSON, then back from them.
QString linkStateName(LinkState state)
{
    return nameIn(kLinkStates, state);
}
QString frameStatusName(FrameStatus status)
{
    return ::frameStatusName(status);
}
QString frameDirectionName(FrameDirection direction)
{
    return nameIn(kFrameDirections, direction);
}
QString frameTransportName(FrameTransport transport)
{
    return ::frameTransportName(transport);
}
std::optional<LinkState> linkStateFromName(const QString& name)
{
    return valueIn(kLinkStates, name);
}
std::optional<FrameStatus> frameStatusFromName(const QString& name)
{
    return valueIn(kFrameStatuses, name);
}
std::optional<FrameDirection> frameDirectionFromName(const QString& name)
{
    return valueIn(kFrameDirections, name);
}
std::optional<FrameTransport> frameTransportFromName(const QString& name)
{
    return valueIn(kFrameTransports, name);
}
bool isStationRole(const QString& role)
{
    return isOneOf(kRoles, role);
}
bool isEventSeverity(const QString& severity)
{
    return isOneOf(kSeverities, severity);
}

}  // namespace BrokerTopics
