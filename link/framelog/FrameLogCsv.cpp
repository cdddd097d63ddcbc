#include "link/framelog/FrameLogCsv.h"

#include "codec/receive/LoggedFrameReading.h"
#include "codec/message/TextFormat.h"
#include "link/framelog/FrameLogReader.h"

#include <QDateTime>

#include <climits>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace {

// Sorts columns: unit kind, then keyed units before keyless ones, then the
// key (text, number), then the occurrence of that unit name in a frame, then
// the item's place in the unit.
using ColumnKey = std::tuple<int, int, std::string, std::int64_t, int, int>;

struct Cell {
    ColumnKey key;
    std::string column;
    std::string value;
};

void addUnit(rcm::Message& message, const rcm::Unit& unit)
{
    if (std::vector<rcm::Unit>* units = message.repeated(unit.kind()))
        units->push_back(unit);
    else
        *message.single(unit.kind()) = unit;
}

// Calls f(name, value) for every item line of the text format; `section`
// receives the outermost section's name.
template <typename F>
void forEachItemLine(const std::string& text, std::string* section, F&& f)
{
    static constexpr std::string_view kBegin = "BEGIN ";
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        const std::string_view line(text.data() + start, end - start);
        start = end + 1;
        if (line.substr(0, kBegin.size()) == kBegin) {
            if (section->empty())
                *section = std::string(line.substr(kBegin.size()));
            continue;
        }
        if (line == "END" || line.empty())
            continue;
        const std::size_t space = line.find(' ');
        if (space == std::string_view::npos)
            f(line, std::string_view());
        else
            f(line.substr(0, space), line.substr(space + 1));
    }
}

// Formatting one unit at a time is what lets a value be attributed to its
// unit without this file knowing how the text format lays a message out.
std::vector<Cell> cellsOf(const rcm::Message& message)
{
    std::vector<Cell> cells;
    std::map<std::string, int> occurrences;
    message.forEachUnit([&](const rcm::Unit& unit) {
        if (unit.empty())
            return;
        rcm::Message single;
        addUnit(single, unit);
        std::string column = rcm::describeUnit(unit);
        const int occurrence = occurrences[column]++;
        if (occurrence > 0)
            column += "#" + std::to_string(occurrence + 1);
        int keyless = 0;
        std::string keyText;
        std::int64_t keyNumber = 0;
        if (const auto key = rcm::unitKey(unit.kind())) {
            if (const rcm::Value* v = unit.find(*key)) {
                keyText = v->text;
                keyNumber = v->number;
            } else {
                keyless = 1;
            }
        }
        const int kind = static_cast<int>(unit.kind());
        std::string section;
        forEachItemLine(rcm::formatMessage(single), &section, [&](std::string_view name, std::string_view value) {
            const rcm::ItemInfo* info = rcm::findItem(unit.kind(), name);
            const int rank = info ? rcm::canonicalRank(info->id) : INT_MAX;
            cells.push_back({ColumnKey{kind, keyless, keyText, keyNumber, occurrence, rank},
                             column + "." + std::string(name), std::string(value)});
        });
    });

    // The flight plan is not a unit of items: its columns are named by its section and its lines.
    rcm::Message plan;
    plan.flightPlan = message.flightPlan;
    std::string section;
    std::vector<std::pair<std::string, std::string>> lines;
    forEachItemLine(rcm::formatMessage(plan), &section,
                    [&](std::string_view name, std::string_view value) { lines.emplace_back(name, value); });
    for (int i = 0; i < int(lines.size()); ++i)
        cells.push_back({ColumnKey{rcm::kUnitKindCount, 0, {}, 0, 0, i}, section + "." + lines[i].first,
                         std::move(lines[i].second)});
    return cells;
}

rcm::LoggedFrameReading decode(const FrameRecord& record, const rcm::LogKey* key)
{
    return rcm::readLoggedFrame(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(record.bytes.constData()),
                                      std::size_t(record.bytes.size())),
        record.enciphered, key);
}

// A refused plain frame's items are what could be read, with its reading
// beside them saying it was refused; a keyed link's refused frame has none.
bool shown(const rcm::LoggedFrameReading& r)
{
    return r.outcome == rcm::LoggedFrameReading::Outcome::Read ||
           r.outcome == rcm::LoggedFrameReading::Outcome::Refused;
}

QByteArray readingText(const rcm::LoggedFrameReading& r)
{
    using O = rcm::LoggedFrameReading::Outcome;
    switch (r.outcome) {
    case O::Read:
        return "read";
    case O::Refused:
    {
        const std::string_view name = rcm::refusalName(*r.refusal);
        return "refused as " + QByteArray(name.data(), qsizetype(name.size()));
    }
    case O::Enciphered:
        return "enciphered";
    case O::NotAFrame:
        break;
    }
    return "not a frame";
}

QByteArray isoMicros(qint64 utcMicros)
{
    qint64 seconds = utcMicros / 1000000;
    qint64 micros = utcMicros % 1000000;
    if (micros < 0) {
        micros += 1000000;
        --seconds;
    }
    const QDateTime t = QDateTime::fromSecsSinceEpoch(seconds, Qt::UTC);
    return t.toString(QStringLiteral("yyyy-MM-ddTHH:mm:ss")).toLatin1() + '.' +
           QByteArray::number(micros).rightJustified(6, '0') + 'Z';
}

// Each field ends in a comma; endRow() turns the last one into the line end.
void appendField(QByteArray& row, QByteArrayView field)
{
    bool quote = false;
    for (char c : field)
        if (c == ',' || c == '"' || c == '\r' || c == '\n')
            quote = true;
    if (!quote) {
        row += field;
    } else {
        row += '"';
        for (char c : field) {
            if (c == '"')
                row += '"';
            row += c;
        }
        row += '"';
    }
    row += ',';
}

void endRow(QByteArray& row)
{
    row.chop(1);
    row += "\r\n";
}

QByteArray correctedText(const FrameRecord& record, const rcm::LoggedFrameReading& reading, int block)
{
    if (record.correctedSymbols.size() > block)
        return QByteArray::number(record.correctedSymbols[block]);
    if (reading.outcome != rcm::LoggedFrameReading::Outcome::NotAFrame)
        return QByteArray::number(block == 0 ? reading.blocks.corrected.block1 : reading.blocks.corrected.block2);
    return {};
}

}  // namespace

bool exportFrameLogCsv(const QString& pcapngPath, QIODevice& out, QString* error, const rcm::LogKey* key)
{
    auto fail = [error](const QString& why) {
        if (error)
            *error = why;
        return false;
    };
    if (!out.isWritable())
        return fail(QStringLiteral("the CSV output is not open for writing"));

    FrameLogReader reader;
    const bool complete = reader.open(pcapngPath);
    if (!complete && reader.count() == 0)
        return fail(reader.errorString());

    std::map<ColumnKey, std::string> columns;
    for (int i = 0; i < reader.count(); ++i) {
        const rcm::LoggedFrameReading d = decode(reader.recordAt(i), key);
        if (shown(d))
            for (Cell& c : cellsOf(d.decoded.message))
                columns.emplace(c.key, std::move(c.column));
    }
    std::unordered_map<std::string, int> columnIndex;
    QByteArray header;
    for (const char* fixed :
         {"utc", "direction", "transport", "status", "corrected_block1", "corrected_block2", "reading"})
        appendField(header, fixed);
    for (const auto& [key, name] : columns)
        if (columnIndex.emplace(name, int(columnIndex.size())).second)
            appendField(header, QByteArray::fromStdString(name));
    endRow(header);
    auto write = [&out](const QByteArray& row) { return out.write(row) == row.size(); };
    if (!write(header))
        return fail(QStringLiteral("writing the CSV failed: %1").arg(out.errorString()));

    std::vector<std::string> values(columnIndex.size());
    for (int i = 0; i < reader.count(); ++i) {
        const FrameRecord record = reader.recordAt(i);
        const rcm::LoggedFrameReading d = decode(record, key);
        for (std::string& v : values)
            v.clear();
        if (shown(d))
            for (const Cell& c : cellsOf(d.decoded.message))
                values[std::size_t(columnIndex.at(c.column))] = c.value;

        QByteArray row;
        appendField(row, isoMicros(record.utcMicros));
        appendField(row, record.direction == FrameDirection::Sent ? "sent" : "received");
        appendField(row, frameTransportName(record.transport).toLatin1());
        appendField(row, frameStatusName(record.status).toLatin1());
        appendField(row, correctedText(record, d, 0));
        appendField(row, correctedText(record, d, 1));
        appendField(row, readingText(d));
        for (const std::string& v : values)
            appendField(row, QByteArrayView(v.data(), qsizetype(v.size())));
        endRow(row);
        if (!write(row))
            return fail(QStringLiteral("writing the CSV failed at frame %1: %2").arg(i).arg(out.errorString()));
    }
    if (!complete)
        return fail(QStringLiteral("the log is unreadable after frame %1, so the frames up to it were exported: %2")
                        .arg(reader.count())
                        .arg(reader.errorString()));
    return true;
}
