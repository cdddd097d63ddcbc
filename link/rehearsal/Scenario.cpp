#include "link/rehearsal/Scenario.h"

#include "codec/message/ItemTable.h"
#include "codec/message/TextFormat.h"
#include "link/airframe/AirframeLoader.h"
#include "link/json/JsonPosition.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QHash>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <algorithm>
#include <cmath>

namespace {

// `//` comments blanked to spaces, so that offsets stay those of the file.
QByteArray withoutComments(QByteArray text)
{
    bool inString = false;
    for (qsizetype i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n')
                text[i++] = ' ';
        }
    }
    return text;
}

// Offsets of every value in a JSON text that QJsonDocument has accepted, by
// its path: "/steps/3" for the fourth step, "/steps/3/within" for a member.
// QJsonDocument keeps no positions, and errors must say where.
class JsonOffsets {
public:
    explicit JsonOffsets(const QByteArray& text) : m_text(text) { value(QString()); }
    int at(const QString& path) const { return m_offsets.value(path, 0); }

private:
    void skipSpace()
    {
        while (m_pos < m_text.size() && QChar::isSpace(uchar(m_text[m_pos])))
            ++m_pos;
    }
    QString string()
    {
        const qsizetype start = ++m_pos;
        while (m_pos < m_text.size() && m_text[m_pos] != '"')
            m_pos += m_text[m_pos] == '\\' ? 2 : 1;
        return QString::fromUtf8(m_text.mid(start, m_pos++ - start));
    }
    void value(const QString& path)
    {
        skipSpace();
        m_offsets.insert(path, int(m_pos));
        if (m_pos >= m_text.size())
            return;
        const char c = m_text[m_pos];
        if (c == '{' || c == '[') {
            ++m_pos;
            for (int index = 0;; ++index) {
                skipSpace();
                if (m_pos >= m_text.size() || m_text[m_pos] == '}' || m_text[m_pos] == ']') {
                    ++m_pos;
                    return;
                }
                QString member = QString::number(index);
                if (c == '{') {
                    member = string();
                    skipSpace();
                    ++m_pos;  // ':'
                }
                value(path + QLatin1Char('/') + member);
                skipSpace();
                if (m_pos < m_text.size() && m_text[m_pos] == ',')
                    ++m_pos;
            }
        }
        if (c == '"') {
            string();
            return;
        }
        while (m_pos < m_text.size() && !QByteArrayView(",]} \t\r\n").contains(m_text[m_pos]))
            ++m_pos;
    }

    const QByteArray& m_text;
    qsizetype m_pos = 0;
    QHash<QString, int> m_offsets;
};

struct Reader {
    const QByteArray& text;
    const QString& path;
    const JsonOffsets& offsets;
    ScenarioError* error;

    bool fail(const QString& where, int step, const QString& message) const
    {
        if (error) {
            const JsonLineColumn at = jsonLineColumn(text, offsets.at(where));
            *error = ScenarioError{path, at.line, at.column, step, message};
        }
        return false;
    }
};

struct Unit {
    std::string_view section;
    rcm::UnitKind kind;
};

// The text of a unit's key for `key` ("2", "VHF1", "1"), as the text format reads it.
std::optional<std::string> keyLine(rcm::UnitKind kind, const std::string& key, const rcm::Message& command)
{
    const auto* units = command.repeated(kind);
    const rcm::ItemId keyItem = *rcm::unitKey(kind);
    for (const rcm::Unit& unit : *units) {
        const rcm::Value& value = *unit.find(keyItem);
        const bool match = kind == rcm::UnitKind::Radio ? value.text == key : std::to_string(value.number) == key;
        if (!match)
            continue;
        std::string line(rcm::itemInfo(keyItem).name);
        line += ' ';
        if (kind == rcm::UnitKind::Camera)
            line += value.text + ' ' + key;
        else
            line += key;
        return line;
    }
    return std::nullopt;
}

bool isInteger(double v)
{
    return std::isfinite(v) && v == std::floor(v);
}

}  // namespace

QString ScenarioError::text() const
{
    QString where = QStringLiteral("%1:%2:%3: ").arg(file).arg(line).arg(column);
    if (step > 0)
        where += QStringLiteral("step %1: ").arg(step);
    return where + message;
}

std::optional<rcm::Message> parseUnitLine(const QString& line, const rcm::Message& command, QString* error)
{
    std::string text = line.toStdString();
    const auto colon = text.find(':');
    const auto space = text.find(' ');
    if (colon != std::string::npos && space != std::string::npos && space < colon) {
        const std::string section = text.substr(0, space);
        const std::string key = text.substr(space + 1, colon - space - 1);
        const auto kind = rcm::unitKindFromSection(section);
        if (!kind || !rcm::isRepeated(*kind)) {
            if (error)
                *error = QStringLiteral("\"%1\" is not a repeated unit (engine, comms_system, camera)")
                             .arg(QString::fromStdString(section));
            return std::nullopt;
        }
        const auto keyText = keyLine(*kind, key, command);
        if (!keyText) {
            if (error)
                *error = QStringLiteral("the aircraft has no %1 %2")
                             .arg(QString::fromStdString(section), QString::fromStdString(key));
            return std::nullopt;
        }
        text = *keyText + '\n' + text.substr(colon + 1);
    }
    const rcm::ParseResult parsed = rcm::parseMessage(text);
    if (!parsed.ok()) {
        if (error)
            *error = QStringLiteral("\"%1\": %2").arg(line, QString::fromStdString(parsed.errors.front().message));
        return std::nullopt;
    }
    return parsed.message;
}

namespace {

// "frame" for one, "frames" for any other count.
QString countedNoun(qint64 count, const QString& noun)
{
    return count == 1 ? noun : noun + QLatin1Char('s');
}

// The unit of `target` that `unit` names: the single one, or the repeated one with its key.
template <typename M>
auto* matchingUnit(M& target, const rcm::Unit& unit)
{
    using U = std::remove_reference_t<decltype(*target.single(unit.kind()))>;
    if (!rcm::isRepeated(unit.kind()))
        return target.single(unit.kind());
    const rcm::ItemId key = *rcm::unitKey(unit.kind());
    for (U& candidate : *target.repeated(unit.kind()))
        if (*candidate.find(key) == *unit.find(key))
            return &candidate;
    return static_cast<U*>(nullptr);
}

}  // namespace

void applyItems(rcm::Message& command, const rcm::Message& items)
{
    items.forEachUnit([&](const rcm::Unit& unit) {
        if (unit.empty())
            return;
        if (rcm::Unit* target = matchingUnit(command, unit))
            for (const rcm::ItemValue& item : unit.items())
                target->set(item.id, item.value);
    });
}

bool reportsItems(const rcm::Message& status, const rcm::Message& items)
{
    bool all = true;
    items.forEachUnit([&](const rcm::Unit& unit) {
        if (unit.empty())
            return;
        const rcm::Unit* reported = matchingUnit(status, unit);
        for (const rcm::ItemValue& item : unit.items()) {
            const rcm::Value* value = reported ? reported->find(item.id) : nullptr;
            all = all && value && *value == item.value;
        }
    });
    return all;
}

QString ScenarioStep::describe() const
{
    QString what;
    switch (kind) {
        case Kind::Set:
            what = QStringLiteral("set %1").arg(text);
            break;
        case Kind::Fault: {
            static const char* const names[] = {"ber", "outage", "slip", "burst", "clear", "call-drop"};
            if (fault.kind == FaultSpec::Kind::Clear)
                what = QStringLiteral("clear faults");
            else if (fault.kind == FaultSpec::Kind::CallDrop)
                what = QStringLiteral("drop the call");
            else
                what = QStringLiteral("fault %1 %2").arg(QLatin1String(names[int(fault.kind)])).arg(fault.value);
            if (fault.direction != FaultDirection::Both)
                what += fault.direction == FaultDirection::Up ? QStringLiteral(" up") : QStringLiteral(" down");
            break;
        }
        case Kind::Upload:
            what = QStringLiteral("upload %1").arg(text);
            break;
        case Kind::ExpectReported:
            what = QStringLiteral("expect \"%1\" reported within %2 s").arg(text).arg(within);
            break;
        case Kind::ExpectAlarm:
            what = QStringLiteral("expect alarm %1 within %2 s").arg(text).arg(within);
            break;
        case Kind::ExpectPlan:
            what = QStringLiteral("expect plan acknowledged within %1 s").arg(within);
            break;
        case Kind::ExpectWrongFrames:
            what = QStringLiteral("expect %1 wrong %2")
                       .arg(QString::number(count), countedNoun(count, QStringLiteral("frame")));
            break;
        case Kind::ExpectFramesLost:
            what = QStringLiteral("expect at most %1 %2 lost")
                       .arg(QString::number(count), countedNoun(count, QStringLiteral("frame")));
            break;
        case Kind::ExpectLinkLostAtMost:
            what = QStringLiteral("expect the link-loss alarm at most %1 %2")
                       .arg(QString::number(count), countedNoun(count, QStringLiteral("time")));
            break;
    }
    const QString when = at ? QStringLiteral(" at %1 s").arg(*at) : QStringLiteral(" over the whole run");
    return QStringLiteral("step %1%2: %3").arg(number).arg(when, what);
}

std::optional<Scenario> Scenario::load(const QString& path, const PlanLoader& loadPlan, ScenarioError* error)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        if (error)
            *error = ScenarioError{path, 0, 0, -1, QStringLiteral("cannot read: %1").arg(file.errorString())};
        return std::nullopt;
    }
    return fromJson(file.readAll(), path, loadPlan, error);
}

namespace {

// The members of a scenario beside its steps: name, airframe, transport, key, speed, duration.
bool readSettings(const Reader& reader, const QJsonObject& root, const QDir& base, Scenario& scenario)
{
    using Transport = Scenario::Transport;
    static const QStringList known = {QStringLiteral("name"), QStringLiteral("airframe"), QStringLiteral("transport"),
                                      QStringLiteral("key"),  QStringLiteral("speed"),    QStringLiteral("duration"),
                                      QStringLiteral("steps")};
    for (auto it = root.begin(); it != root.end(); ++it)
        if (!known.contains(it.key()))
            return reader.fail(
                QStringLiteral("/") + it.key(), -1,
                QStringLiteral("unknown member \"%1\" (known: %2)").arg(it.key(), known.join(QStringLiteral(", "))));

    scenario.name = root.value(QStringLiteral("name")).toString(QFileInfo(scenario.path).completeBaseName());
    scenario.airframeName = root.value(QStringLiteral("airframe")).toString(QStringLiteral("well-equipped"));
    QString airframeError;
    const QString builtIn = QStringLiteral(":/airframes/%1.json").arg(scenario.airframeName);
    const QString airframePath =
        AirframeLoader::builtIn().contains(builtIn) ? builtIn : base.absoluteFilePath(scenario.airframeName);
    const auto airframe = AirframeLoader::load(airframePath, &airframeError);
    if (!airframe)
        return reader.fail(QStringLiteral("/airframe"), -1, airframeError);
    scenario.airframe = *airframe;

    const QString transport = root.value(QStringLiteral("transport")).toString(QStringLiteral("udp"));
    static const QStringList transports = {QStringLiteral("udp"), QStringLiteral("serial"), QStringLiteral("modem")};
    if (!transports.contains(transport))
        return reader.fail(QStringLiteral("/transport"), -1,
                           QStringLiteral("transport is \"udp\", \"serial\" or \"modem\""));
    scenario.transport = Transport(transports.indexOf(transport));
    if (root.contains(QStringLiteral("key")) && !root.value(QStringLiteral("key")).isBool())
        return reader.fail(QStringLiteral("/key"), -1, QStringLiteral("key is true or false"));
    scenario.key = root.value(QStringLiteral("key")).toBool();
    scenario.speed = root.value(QStringLiteral("speed")).toDouble(1);
    if (!(scenario.speed >= 1))
        return reader.fail(QStringLiteral("/speed"), -1, QStringLiteral("speed is a number, 1 or more"));
    if (scenario.transport == Transport::Modem && scenario.speed != 1)
        return reader.fail(QStringLiteral("/speed"), -1,
                           QStringLiteral("the modem transport runs at speed 1: the modem model keeps real time"));
    scenario.duration = root.value(QStringLiteral("duration")).toDouble(-1);
    if (!(scenario.duration > 0))
        return reader.fail(QStringLiteral("/duration"), -1, QStringLiteral("duration is seconds, more than 0"));
    return true;
}

// Reads one member of "steps"; its errors name the step and the member.
class StepReader {
public:
    StepReader(const Reader& reader, const Scenario& scenario, const rcm::Message& command, const QDir& base,
               const Scenario::PlanLoader& loadPlan, int index)
        : m_reader(reader),
          m_scenario(scenario),
          m_command(command),
          m_base(base),
          m_loadPlan(loadPlan),
          m_where(QStringLiteral("/steps/%1").arg(index)),
          m_number(index + 1)
    {
    }

    bool read(const QJsonValue& json, ScenarioStep& step) const
    {
        if (!json.isObject())
            return fail(QString(), QStringLiteral("a step is an object"));
        const QJsonObject object = json.toObject();
        step.number = m_number;
        const JsonLineColumn at = jsonLineColumn(m_reader.text, m_reader.offsets.at(m_where));
        step.line = at.line;
        step.column = at.column;
        if (object.contains(QStringLiteral("at"))) {
            const double at = object.value(QStringLiteral("at")).toDouble(-1);
            if (at < 0 || at > m_scenario.duration)
                return fail(QStringLiteral("at"),
                            QStringLiteral("at is seconds from 0 to the duration, %1").arg(m_scenario.duration));
            step.at = at;
        }
        QString action;
        if (!readAction(object, step, &action))
            return false;
        const QJsonValue value = object.value(action);
        if (action == QLatin1String("set"))
            return readSet(value, step);
        if (action == QLatin1String("upload"))
            return readUpload(value, step);
        if (action == QLatin1String("fault"))
            return readFault(value, step);
        return readExpect(object, value, step);
    }

private:
    bool fail(const QString& member, const QString& message) const
    {
        return m_reader.fail(member.isEmpty() ? m_where : m_where + QLatin1Char('/') + member, m_number, message);
    }

    // The one action of a step (set, fault, upload or expect), its members checked.
    bool readAction(const QJsonObject& object, const ScenarioStep& step, QString* action) const
    {
        const QStringList actions = {QStringLiteral("set"), QStringLiteral("fault"), QStringLiteral("upload"),
                                     QStringLiteral("expect")};
        QStringList found;
        for (auto it = object.begin(); it != object.end(); ++it) {
            if (actions.contains(it.key()))
                found << it.key();
            else if (it.key() != QLatin1String("at") && it.key() != QLatin1String("within"))
                return fail(it.key(), QStringLiteral("unknown member \"%1\" (a step has at, one of %2, and within "
                                                     "with expect)")
                                          .arg(it.key(), actions.join(QStringLiteral(", "))));
        }
        if (found.size() != 1)
            return fail(QString(), QStringLiteral("a step has exactly one of set, fault, upload, expect"));
        *action = found.front();
        if (*action != QLatin1String("expect") && !step.at)
            return fail(QString(), QStringLiteral("%1 needs \"at\"").arg(*action));
        // "within" belongs to an expectation: beside "expect", as
        // docs/rehearsal.md writes it, or inside it.
        if (object.contains(QStringLiteral("within")) && *action != QLatin1String("expect"))
            return fail(QStringLiteral("within"),
                        QStringLiteral("within goes with expect: the seconds after \"at\" it may take to hold"));
        return true;
    }

    bool readSet(const QJsonValue& value, ScenarioStep& step) const
    {
        step.kind = ScenarioStep::Kind::Set;
        step.text = value.toString();
        return readItems(QStringLiteral("set"), step);
    }

    // The items a step's text ("camera 1: cam_zoom_set 40") names, read at `member`.
    bool readItems(const QString& member, ScenarioStep& step) const
    {
        QString why;
        const auto items = parseUnitLine(step.text, m_command, &why);
        if (!items)
            return fail(member, why);
        step.items = *items;
        return true;
    }

    bool readUpload(const QJsonValue& value, ScenarioStep& step) const
    {
        step.kind = ScenarioStep::Kind::Upload;
        step.text = value.toString();
        QString why = QStringLiteral("no plan loader");
        const auto plan = m_loadPlan ? m_loadPlan(m_base.absoluteFilePath(step.text), &why) : std::nullopt;
        if (!plan)
            return fail(QStringLiteral("upload"), why);
        step.plan = *plan;
        return true;
    }

    bool readFault(const QJsonValue& value, ScenarioStep& step) const
    {
        step.kind = ScenarioStep::Kind::Fault;
        const bool modem = m_scenario.transport == Scenario::Transport::Modem;
        if (value.toString() == QLatin1String("clear")) {
            step.fault.kind = FaultSpec::Kind::Clear;
            return true;
        }
        if (value.toString() == QLatin1String("call-drop")) {
            if (!modem)
                return fail(QStringLiteral("fault"), QStringLiteral("call-drop needs \"transport\": \"modem\""));
            step.fault.kind = FaultSpec::Kind::CallDrop;
            return true;
        }
        if (modem)
            return fail(QStringLiteral("fault"),
                        QStringLiteral("the modem transport's faults are \"call-drop\" and \"clear\": "
                                       "its bytes go through the modem model, not the fault channel"));
        if (!value.isObject())
            return fail(QStringLiteral("fault"), QStringLiteral("a fault is an object, \"clear\" or \"call-drop\""));
        return readChannelFault(value.toObject(), step.fault);
    }

    // {"ber": p}, {"outage": s}, {"slip": p} or {"burst": p}, with an optional direction.
    bool readChannelFault(const QJsonObject& object, FaultSpec& fault) const
    {
        static const QStringList kinds = {QStringLiteral("ber"), QStringLiteral("outage"), QStringLiteral("slip"),
                                          QStringLiteral("burst")};
        QStringList given;
        for (auto it = object.begin(); it != object.end(); ++it) {
            if (kinds.contains(it.key()))
                given << it.key();
            else if (it.key() != QLatin1String("direction"))
                return fail(QStringLiteral("fault/") + it.key(),
                            QStringLiteral("unknown fault \"%1\" (ber, outage, slip, burst, direction)").arg(it.key()));
        }
        if (given.size() != 1)
            return fail(QStringLiteral("fault"), QStringLiteral("a fault step has one of ber, outage, slip, burst"));
        fault.kind = FaultSpec::Kind(kinds.indexOf(given.front()));
        fault.value = object.value(given.front()).toDouble(-1);
        const bool seconds = fault.kind == FaultSpec::Kind::Outage;
        if (seconds ? !(fault.value > 0) : !(fault.value >= 0 && fault.value <= 1))
            return fail(QStringLiteral("fault/") + given.front(),
                        seconds ? QStringLiteral("outage is seconds, more than 0")
                                : QStringLiteral("%1 is a probability from 0 to 1").arg(given.front()));
        const QString direction = object.value(QStringLiteral("direction")).toString(QStringLiteral("both"));
        static const QStringList directions = {QStringLiteral("both"), QStringLiteral("up"), QStringLiteral("down")};
        if (!directions.contains(direction))
            return fail(QStringLiteral("fault/direction"), QStringLiteral("direction is \"up\" or \"down\""));
        fault.direction = FaultDirection(directions.indexOf(direction));
        return true;
    }

    bool readExpect(const QJsonObject& object, const QJsonValue& value, ScenarioStep& step) const
    {
        if (!value.isObject())
            return fail(QStringLiteral("expect"), QStringLiteral("expect is an object"));
        const QJsonObject expect = value.toObject();
        const bool withinBeside = object.contains(QStringLiteral("within"));
        if (withinBeside && expect.contains(QStringLiteral("within")))
            return fail(QStringLiteral("within"),
                        QStringLiteral("within is given twice, beside expect and in it; give it once"));
        const QJsonValue within =
            withinBeside ? object.value(QStringLiteral("within")) : expect.value(QStringLiteral("within"));
        if (expect.contains(QStringLiteral("reported"))) {
            step.kind = ScenarioStep::Kind::ExpectReported;
            step.text = expect.value(QStringLiteral("reported")).toString();
            return readItems(QStringLiteral("expect/reported"), step) && readWithin(within, step);
        }
        if (expect.contains(QStringLiteral("alarm"))) {
            step.kind = ScenarioStep::Kind::ExpectAlarm;
            step.text = expect.value(QStringLiteral("alarm")).toString();
            if (step.text != QLatin1String("link-lost") && step.text != QLatin1String("link-regained"))
                return fail(QStringLiteral("expect/alarm"),
                            QStringLiteral("alarm is \"link-lost\" or \"link-regained\""));
            return readWithin(within, step);
        }
        if (expect.contains(QStringLiteral("plan"))) {
            step.kind = ScenarioStep::Kind::ExpectPlan;
            step.text = expect.value(QStringLiteral("plan")).toString();
            if (step.text != QLatin1String("acknowledged"))
                return fail(QStringLiteral("expect/plan"), QStringLiteral("plan is \"acknowledged\""));
            return readWithin(within, step);
        }
        return readCount(expect, within, withinBeside, step);
    }

    // An expectation that holds at a time needs "at" and "within".
    bool readWithin(const QJsonValue& within, ScenarioStep& step) const
    {
        step.within = within.toDouble(-1);
        if (!step.at || step.within < 0)
            return fail(QStringLiteral("expect"),
                        QStringLiteral("this expectation needs \"at\" and \"within\" (seconds)"));
        return true;
    }

    // A count that holds over the whole run: wrong-frames, frames-lost-at-most, link-lost-at-most.
    bool readCount(const QJsonObject& expect, const QJsonValue& within, bool withinBeside, ScenarioStep& step) const
    {
        static const QStringList counts = {QStringLiteral("wrong-frames"), QStringLiteral("frames-lost-at-most"),
                                           QStringLiteral("link-lost-at-most")};
        static const ScenarioStep::Kind kinds[] = {ScenarioStep::Kind::ExpectWrongFrames,
                                                   ScenarioStep::Kind::ExpectFramesLost,
                                                   ScenarioStep::Kind::ExpectLinkLostAtMost};
        const auto found =
            std::find_if(counts.begin(), counts.end(), [&](const QString& c) { return expect.contains(c); });
        if (found == counts.end())
            return fail(QStringLiteral("expect"), QStringLiteral("expect one of reported, alarm, plan, wrong-frames, "
                                                                 "frames-lost-at-most, link-lost-at-most"));
        const QString member = *found;
        step.kind = kinds[found - counts.begin()];
        const double count = expect.value(member).toDouble(-1);
        if (!isInteger(count) || count < 0)
            return fail(QStringLiteral("expect/") + member,
                        QStringLiteral("%1 is a whole number, 0 or more").arg(member));
        step.count = qint64(count);
        if (step.at)
            return fail(QStringLiteral("at"), QStringLiteral("%1 holds over the whole run: no \"at\"").arg(member));
        if (!within.isUndefined())
            return fail(withinBeside ? QStringLiteral("within") : QStringLiteral("expect/within"),
                        QStringLiteral("%1 holds over the whole run: no \"within\"").arg(member));
        return true;
    }

    const Reader& m_reader;
    const Scenario& m_scenario;
    const rcm::Message& m_command;
    const QDir& m_base;
    const Scenario::PlanLoader& m_loadPlan;
    const QString m_where;
    const int m_number;
};

}  // namespace

std::optional<Scenario> Scenario::fromJson(const QByteArray& raw, const QString& path, const PlanLoader& loadPlan,
                                           ScenarioError* error)
{
    const QByteArray text = withoutComments(raw);
    QJsonParseError parseError;
    const QJsonDocument document = QJsonDocument::fromJson(text, &parseError);
    if (parseError.error != QJsonParseError::NoError || !document.isObject()) {
        if (error) {
            const JsonLineColumn at = jsonLineColumn(text, parseError.offset);
            const QString why = parseError.error != QJsonParseError::NoError ? parseError.errorString()
                                                                             : QStringLiteral("not a JSON object");
            *error = ScenarioError{path, at.line, at.column, -1, why};
        }
        return std::nullopt;
    }
    const JsonOffsets offsets(text);
    const Reader reader{text, path, offsets, error};
    const QJsonObject root = document.object();
    const QDir base = QFileInfo(path).absoluteDir();

    Scenario scenario;
    scenario.path = path;
    if (!readSettings(reader, root, base, scenario))
        return std::nullopt;
    const rcm::Message command = rcm::restingCommand(scenario.airframe);
    const QJsonArray steps = root.value(QStringLiteral("steps")).toArray();
    for (int i = 0; i < steps.size(); ++i) {
        ScenarioStep step;
        if (!StepReader(reader, scenario, command, base, loadPlan, i).read(steps[i], step))
            return std::nullopt;
        scenario.steps.push_back(std::move(step));
    }
    return scenario;
}
