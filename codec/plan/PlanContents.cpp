#include "codec/plan/PlanContents.h"

#include <limits>
#include <stdexcept>

namespace rcm::plan {

namespace {

constexpr std::size_t kMaxCount = std::numeric_limits<std::uint16_t>::max();

class Writer {
public:
    void u8(std::uint8_t v) { m_out.push_back(v); }
    void u16(std::uint16_t v)
    {
        u8(std::uint8_t(v >> 8));
        u8(std::uint8_t(v));
    }
    void u32(std::uint32_t v)
    {
        u16(std::uint16_t(v >> 16));
        u16(std::uint16_t(v));
    }
    void i32(std::int32_t v) { u32(std::uint32_t(v)); }
    void position(const Position& p)
    {
        i32(p.latitude);
        i32(p.longitude);
    }
    std::vector<std::uint8_t> take() { return std::move(m_out); }

private:
    std::vector<std::uint8_t> m_out;
};

// Reads big-endian numbers and remembers the first place it ran short, so a
// decoder can check once per record instead of once per field.
class Reader {
public:
    explicit Reader(std::span<const std::uint8_t> bytes) : m_bytes(bytes) {}
    std::size_t offset() const { return m_at; }
    std::size_t left() const { return m_bytes.size() - m_at; }
    bool has(std::size_t n) const { return left() >= n; }
    std::uint8_t u8() { return m_bytes[m_at++]; }
    std::uint16_t u16()
    {
        const std::uint16_t hi = u8();
        return std::uint16_t(hi << 8 | u8());
    }
    std::uint32_t u32()
    {
        const std::uint32_t hi = u16();
        return hi << 16 | u16();
    }
    std::int32_t i32() { return std::int32_t(u32()); }
    Position position()
    {
        Position p;
        p.latitude = i32();
        p.longitude = i32();
        return p;
    }

private:
    std::span<const std::uint8_t> m_bytes;
    std::size_t m_at = 0;
};

void checkCount(std::size_t count, const char* what)
{
    if (count > kMaxCount)
        throw std::invalid_argument(std::to_string(count) + " " + what + "; the plan bytes hold at most 65535");
}

std::uint16_t saturate(std::size_t n)
{
    return std::uint16_t(n > kMaxCount ? kMaxCount : n);
}

}  // namespace

std::uint8_t Contents::format() const
{
    return polygons.empty() && circles.empty() && rallyPoints.empty() ? 1 : 2;
}

std::vector<std::uint8_t> encode(const Contents& contents)
{
    checkCount(contents.items.size(), "mission items");
    Writer w;
    const std::uint8_t format = contents.format();
    w.u8(format);
    w.u8(0);
    w.u16(std::uint16_t(contents.items.size()));
    w.i32(contents.homeLatitude);
    w.i32(contents.homeLongitude);
    w.i32(contents.homeAltitude);
    for (const Item& item : contents.items) {
        w.u16(item.seq);
        w.u16(item.command);
        w.u8(item.frame);
        w.u8(item.autoContinue ? 1 : 0);
        for (std::uint32_t p : item.params)
            w.u32(p);
        w.i32(item.x);
        w.i32(item.y);
        w.i32(item.z);
    }
    if (format == 1)
        return w.take();

    checkCount(contents.polygons.size(), "fence polygons");
    w.u16(std::uint16_t(contents.polygons.size()));
    for (std::size_t i = 0; i < contents.polygons.size(); ++i) {
        const FencePolygon& polygon = contents.polygons[i];
        if (polygon.vertices.size() < 3)
            throw std::invalid_argument("fence polygon " + std::to_string(i + 1) + " has " +
                                        std::to_string(polygon.vertices.size()) + " vertices; a polygon needs 3");
        checkCount(polygon.vertices.size(), "vertices in a fence polygon");
        w.u8(polygon.inclusion ? 1 : 0);
        w.u8(0);
        w.u16(std::uint16_t(polygon.vertices.size()));
        for (const Position& p : polygon.vertices)
            w.position(p);
    }
    checkCount(contents.circles.size(), "fence circles");
    w.u16(std::uint16_t(contents.circles.size()));
    for (std::size_t i = 0; i < contents.circles.size(); ++i) {
        const FenceCircle& circle = contents.circles[i];
        if (circle.radius == 0)
            throw std::invalid_argument("fence circle " + std::to_string(i + 1) + " has no radius");
        w.u8(circle.inclusion ? 1 : 0);
        w.u8(0);
        w.position(circle.centre);
        w.u32(circle.radius);
    }
    checkCount(contents.rallyPoints.size(), "rally points");
    w.u16(std::uint16_t(contents.rallyPoints.size()));
    for (const RallyPoint& rally : contents.rallyPoints) {
        w.position(rally.position);
        w.i32(rally.altitude);
    }
    return w.take();
}

namespace {

// A plan being decoded: the reader, and the first error met, said as
// "byte <offset>: <what>".
class Decoding {
public:
    Decoding(std::span<const std::uint8_t> bytes, std::string* error) : r(bytes), m_error(error) {}

    // False, the error said.
    bool refuse(const std::string& what)
    {
        if (m_error)
            *m_error = "byte " + std::to_string(r.offset()) + ": " + what;
        return false;
    }
    // Whether the next need bytes are there; says so when not.
    bool has(const std::string& what, std::size_t need)
    {
        return r.has(need) ||
               refuse(what + " needs " + std::to_string(need) + " bytes; " + std::to_string(r.left()) + " left");
    }
    // A list: its two-byte count (countWhat names it when missing), then each
    // entry read by readEntry(1), readEntry(2), ...; false at the first fault.
    template <typename ReadEntry>
    bool readList(const std::string& countWhat, const ReadEntry& readEntry)
    {
        if (!has(countWhat, 2))
            return false;
        const std::uint16_t count = r.u16();
        for (std::size_t i = 0; i < count; ++i) {
            if (!readEntry(i + 1))
                return false;
        }
        return true;
    }

    // Format 2's lists after the items: fence polygons, fence circles, rally points.
    bool readFenceAndRally(Contents& c);

    Reader r;

private:
    std::string* m_error;
};

bool Decoding::readFenceAndRally(Contents& c)
{
    // Each entry's reader takes the entry and returns true, or says what
    // is wrong and returns false.
    const auto readPolygon = [&](std::size_t number) {
        const std::string name = "fence polygon " + std::to_string(number);
        if (!has(name, 4))
            return false;
        FencePolygon polygon;
        polygon.inclusion = (r.u8() & 1) != 0;
        r.u8();
        const std::uint16_t vertices = r.u16();
        if (vertices < 3)
            return refuse(name + " has " + std::to_string(vertices) + " vertices; a polygon needs 3");
        if (!has(name + "'s " + std::to_string(vertices) + " vertices", 8 * std::size_t(vertices)))
            return false;
        for (std::size_t v = 0; v < vertices; ++v)
            polygon.vertices.push_back(r.position());
        c.polygons.push_back(std::move(polygon));
        return true;
    };
    const auto readCircle = [&](std::size_t number) {
        if (!has("fence circle " + std::to_string(number), 14))
            return false;
        FenceCircle circle;
        circle.inclusion = (r.u8() & 1) != 0;
        r.u8();
        circle.centre = r.position();
        circle.radius = r.u32();
        if (circle.radius == 0)
            return refuse("fence circle " + std::to_string(number) + " has no radius");
        c.circles.push_back(circle);
        return true;
    };
    const auto readRallyPoint = [&](std::size_t number) {
        if (!has("rally point " + std::to_string(number), 12))
            return false;
        // A braced list is read left to right: the position, then the altitude.
        c.rallyPoints.push_back(RallyPoint{r.position(), r.i32()});
        return true;
    };
    return readList("the fence polygon count", readPolygon) && readList("the fence circle count", readCircle) &&
           readList("the rally point count", readRallyPoint);
}

}  // namespace

std::optional<Contents> decode(std::span<const std::uint8_t> bytes, std::string* error)
{
    Decoding d(bytes, error);
    Reader& r = d.r;
    const auto fail = [&](const std::string& what) -> std::optional<Contents> {
        d.refuse(what);
        return std::nullopt;
    };
    if (!d.has("the plan header", kHeaderBytes))
        return std::nullopt;
    Contents c;
    const std::uint8_t format = r.u8();
    if (format != 1 && format != 2)
        return fail("plan format " + std::to_string(format) + "; formats 1 and 2 are known");
    if (r.u8() != 0)
        return fail("the reserved header byte is not 0");
    const std::uint16_t count = r.u16();
    c.homeLatitude = r.i32();
    c.homeLongitude = r.i32();
    c.homeAltitude = r.i32();
    c.items.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        if (!d.has("mission item " + std::to_string(i + 1) + " of " + std::to_string(count), kItemBytes))
            return std::nullopt;
        Item item;
        item.seq = r.u16();
        item.command = r.u16();
        item.frame = r.u8();
        item.autoContinue = (r.u8() & 1) != 0;
        for (std::uint32_t& p : item.params)
            p = r.u32();
        item.x = r.i32();
        item.y = r.i32();
        item.z = r.i32();
        c.items.push_back(item);
    }
    if (format == 2 && !d.readFenceAndRally(c))
        return std::nullopt;
    if (r.left() != 0)
        return fail(std::to_string(r.left()) + (r.left() == 1 ? " byte" : " bytes") + " after the end of a format " +
                    std::to_string(format) + " plan");
    return c;
}

Report Report::of(const Contents& contents)
{
    Report report;
    report.format = contents.format();
    report.items = saturate(contents.items.size());
    report.polygons = saturate(contents.polygons.size());
    std::size_t vertices = 0;
    for (const FencePolygon& p : contents.polygons)
        vertices += p.vertices.size();
    report.vertices = saturate(vertices);
    report.circles = saturate(contents.circles.size());
    report.rallyPoints = saturate(contents.rallyPoints.size());
    return report;
}

std::vector<std::uint8_t> Report::toBytes() const
{
    Writer w;
    w.u8(format);
    w.u16(items);
    w.u16(polygons);
    w.u16(vertices);
    w.u16(circles);
    w.u16(rallyPoints);
    return w.take();
}

std::optional<Report> Report::read(std::span<const std::uint8_t> bytes)
{
    if (bytes.size() != kSize)
        return std::nullopt;
    Reader r(bytes);
    Report report;
    report.format = r.u8();
    report.items = r.u16();
    report.polygons = r.u16();
    report.vertices = r.u16();
    report.circles = r.u16();
    report.rallyPoints = r.u16();
    return report;
}

std::string Report::describe() const
{
    const auto count = [](std::size_t n, const std::string& one, const std::string& many) {
        return std::to_string(n) + " " + (n == 1 ? one : many);
    };
    std::string text = count(items, "mission item", "mission items") + ", ";
    if (polygons == 0 && circles == 0)
        text += "no fence";
    else {
        text += "fence ";
        if (polygons != 0)
            text += count(polygons, "polygon", "polygons") + " (" + count(vertices, "vertex", "vertices") + ")";
        if (polygons != 0 && circles != 0)
            text += " and ";
        if (circles != 0)
            text += count(circles, "circle", "circles");
    }
    text +=
        ", " + (rallyPoints == 0 ? std::string("no rally points") : count(rallyPoints, "rally point", "rally points"));
    return text;
}

}  // namespace rcm::plan
