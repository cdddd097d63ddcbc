#include "codec/message/FlightPlanTransfer.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rcm {
namespace {

constexpr std::array<std::uint32_t, 256> makeCrcTable()
{
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k)
            c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}
constexpr auto kCrcTable = makeCrcTable();

std::uint32_t readU32(const std::uint8_t* p)
{
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

void writeU32(std::uint8_t* p, std::uint32_t v)
{
    p[0] = static_cast<std::uint8_t>(v >> 24);
    p[1] = static_cast<std::uint8_t>(v >> 16);
    p[2] = static_cast<std::uint8_t>(v >> 8);
    p[3] = static_cast<std::uint8_t>(v);
}

// "1 section", "3 sections".
std::string sectionsText(std::uint64_t n)
{
    return std::to_string(n) + (n == 1 ? " section" : " sections");
}

}  // namespace

std::string planIdText(std::uint32_t planId)
{
    static constexpr char kDigits[] = "0123456789ABCDEF";
    std::string text = "0x00000000";
    for (int i = 0; i < 8; ++i)
        text[std::size_t(9 - i)] = kDigits[(planId >> (4 * i)) & 0xF];
    return text;
}

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc)
{
    crc = ~crc;
    for (std::uint8_t b : bytes)
        crc = kCrcTable[(crc ^ b) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

std::optional<FlightPlanDescriptor> FlightPlanDescriptor::read(std::span<const std::uint8_t> bytes)
{
    if (bytes.size() < kSize)
        return std::nullopt;
    FlightPlanDescriptor d;
    d.sectionCount = static_cast<std::uint16_t>((bytes[0] << 8) | bytes[1]);
    d.totalBytes = readU32(bytes.data() + 2);
    d.crc = readU32(bytes.data() + 6);
    return d;
}

void FlightPlanDescriptor::write(std::span<std::uint8_t, kSize> out) const
{
    out[0] = static_cast<std::uint8_t>(sectionCount >> 8);
    out[1] = static_cast<std::uint8_t>(sectionCount);
    writeU32(out.data() + 2, totalBytes);
    writeU32(out.data() + 6, crc);
}

FlightPlanSection FlightPlanAcknowledgement::toSection() const
{
    FlightPlanSection s;
    s.planId = planId;
    s.sectionId = kAcknowledgementSectionId;
    s.data.resize(FlightPlanDescriptor::kSize);
    descriptor.write(std::span<std::uint8_t, FlightPlanDescriptor::kSize>(s.data.data(), FlightPlanDescriptor::kSize));
    s.data.insert(s.data.end(), report.begin(), report.begin() + std::ptrdiff_t(std::min(report.size(), kMaxReport)));
    return s;
}

std::optional<FlightPlanAcknowledgement> FlightPlanAcknowledgement::read(const FlightPlanSection& section)
{
    if (section.sectionId != kAcknowledgementSectionId || section.planId == 0 ||
        section.data.size() < FlightPlanDescriptor::kSize)
        return std::nullopt;
    return FlightPlanAcknowledgement{section.planId, *FlightPlanDescriptor::read(section.data),
                                     {section.data.begin() + FlightPlanDescriptor::kSize, section.data.end()}};
}

FlightPlanUploader::FlightPlanUploader(std::uint32_t planId, std::span<const std::uint8_t> plan,
                                       std::size_t sectionSize, int maxPasses)
    : m_planId(planId), m_maxPasses(std::max(maxPasses, 0))
{
    if (planId == 0)
        throw std::invalid_argument("flight plan ID 0 means \"no flight plan\"; a plan needs a non-zero ID");
    if (sectionSize < FlightPlanDescriptor::kSize || sectionSize > FlightPlanSection::kMaxData)
        throw std::invalid_argument("flight plan section size " + std::to_string(sectionSize) + " is outside " +
                                    std::to_string(FlightPlanDescriptor::kSize) + ".." +
                                    std::to_string(FlightPlanSection::kMaxData));
    if (plan.size() > 0xFFFFFFFFu)
        throw std::invalid_argument("flight plan larger than 4 GiB");

    const std::size_t streamBytes = FlightPlanDescriptor::kSize + plan.size();
    const std::size_t count = (streamBytes + sectionSize - 1) / sectionSize;
    if (count > kMaxFlightPlanSections)
        throw std::invalid_argument("flight plan of " + std::to_string(plan.size()) + " bytes needs " +
                                    sectionsText(count) + " of " + std::to_string(sectionSize) +
                                    " bytes, more than the " + std::to_string(kMaxFlightPlanSections) +
                                    " section IDs available");

    m_descriptor.sectionCount = static_cast<std::uint16_t>(count);
    m_descriptor.totalBytes = static_cast<std::uint32_t>(plan.size());
    m_descriptor.crc = crc32(plan);

    std::vector<std::uint8_t> stream(streamBytes);
    m_descriptor.write(
        std::span<std::uint8_t, FlightPlanDescriptor::kSize>(stream.data(), FlightPlanDescriptor::kSize));
    std::copy(plan.begin(), plan.end(), stream.begin() + FlightPlanDescriptor::kSize);

    m_sections.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t begin = i * sectionSize;
        const std::size_t end = std::min(begin + sectionSize, streamBytes);
        FlightPlanSection s;
        s.planId = planId;
        s.sectionId = static_cast<std::uint16_t>(i);
        s.data.assign(stream.begin() + static_cast<std::ptrdiff_t>(begin),
                      stream.begin() + static_cast<std::ptrdiff_t>(end));
        m_sections.push_back(std::move(s));
    }
}

FlightPlanUploader::Progress FlightPlanUploader::progress() const
{
    // m_next wraps to 0 as the last section of a pass goes out.
    const std::size_t inPass = m_pass == 0 ? 0 : (m_next == 0 ? m_sections.size() : m_next);
    return Progress{m_sent, m_sections.size(), inPass, m_pass, m_maxPasses};
}

std::optional<FlightPlanSection> FlightPlanUploader::next()
{
    if (m_state != State::Sending)
        return std::nullopt;
    if (m_next == 0) {
        if (m_maxPasses > 0 && m_pass >= m_maxPasses) {
            m_state = State::GaveUp;
            return std::nullopt;
        }
        ++m_pass;
    }
    const std::size_t index = m_next;
    m_next = (m_next + 1) % m_sections.size();
    m_sent = std::max(m_sent, index + 1);
    return m_sections[index];
}

bool FlightPlanUploader::handleReply(const FlightPlanSection& reply)
{
    const auto ack = FlightPlanAcknowledgement::read(reply);
    if (!ack || ack->planId != m_planId || ack->descriptor != m_descriptor)
        return false;
    m_state = State::Acknowledged;
    m_report = ack->report;
    return true;
}

void FlightPlanAssembler::reset()
{
    restart(0);
    m_lastComplete.reset();
}

void FlightPlanAssembler::restart(std::uint32_t planId)
{
    m_planId = planId;
    m_descriptor.reset();
    m_sections.clear();
    m_lastId.reset();
    m_highestId.reset();
    m_wrapped = false;
}

FlightPlanAssembler::Result FlightPlanAssembler::progress(Result::Kind kind) const
{
    Result r;
    r.kind = kind;
    r.planId = m_planId;
    r.received = m_sections.size();
    r.total = m_descriptor ? m_descriptor->sectionCount : 0;
    return r;
}

std::vector<std::uint16_t> FlightPlanAssembler::unheldBelow(std::size_t end, std::uint16_t arriving) const
{
    std::vector<std::uint16_t> ids;
    for (std::size_t id = 0; id < end; ++id)
        if (id != arriving && !m_sections.contains(static_cast<std::uint16_t>(id)))
            ids.push_back(static_cast<std::uint16_t>(id));
    return ids;
}

FlightPlanAssembler::Result FlightPlanAssembler::failure(std::string what) const
{
    Result r = progress(Result::Kind::Error);
    r.error = "flight plan " + planIdText(m_planId) + ": " + std::move(what);
    return r;
}

FlightPlanAssembler::Result FlightPlanAssembler::add(const FlightPlanSection& section)
{
    using Kind = Result::Kind;
    if (section.empty() || section.sectionId >= kFirstControlSectionId)
        return progress(Kind::None);
    if (section.planId == 0) {
        Result r = progress(Kind::Error);
        r.error = "flight plan ID 0 with section " + std::to_string(section.sectionId) + " and " +
                  std::to_string(section.data.size()) + " data bytes; ID 0 means no flight plan";
        return r;
    }

    const std::uint16_t id = section.sectionId;
    std::optional<FlightPlanDescriptor> newDescriptor;
    if (id == 0) {
        newDescriptor = FlightPlanDescriptor::read(section.data);
        if (!newDescriptor) {
            if (section.planId != m_planId)
                restart(section.planId);
            return failure("section 0 holds " + std::to_string(section.data.size()) + " bytes, fewer than the " +
                           std::to_string(FlightPlanDescriptor::kSize) + "-byte descriptor");
        }
    }

    if (m_lastComplete && section.planId == m_lastComplete->planId && section.planId != m_planId &&
        (!newDescriptor || *newDescriptor == m_lastComplete->descriptor)) {
        Result r;
        r.kind = Kind::AlreadyComplete;
        r.planId = section.planId;
        r.received = r.total = m_lastComplete->descriptor.sectionCount;
        return r;
    }
    if (section.planId != m_planId || (newDescriptor && m_descriptor && *newDescriptor != *m_descriptor))
        restart(section.planId);
    if (section.data.empty())
        return failure("section " + std::to_string(id) + " carries no data");

    if (newDescriptor) {
        if (auto refused = adoptDescriptor(*newDescriptor, section))
            return *refused;
    } else if (m_descriptor && id >= m_descriptor->sectionCount) {
        return failure("section " + std::to_string(id) + " lies beyond the " +
                       sectionsText(m_descriptor->sectionCount) + " the descriptor announces");
    }

    const bool skipped = skippedBefore(id);
    const bool complete = m_descriptor && m_sections.size() + !m_sections.contains(id) == m_descriptor->sectionCount;
    // Everything sent and not held, not only this gap: what another pass must bring.
    const std::size_t sentEnd = m_wrapped && m_descriptor ? m_descriptor->sectionCount : *m_highestId + 1u;
    const std::vector<std::uint16_t> missing = skipped ? unheldBelow(sentEnd, id) : std::vector<std::uint16_t>{};
    m_sections.insert_or_assign(id, section.data);

    if (complete)
        return assemble();
    if (missing.empty())
        return progress(Kind::InProgress);
    Result r = progress(Kind::Missing);
    r.missing = missing;
    return r;
}

// What is wrong with a descriptor that section 0 (`section0Bytes` long)
// holds; empty when nothing is.
std::string FlightPlanAssembler::descriptorFault(const FlightPlanDescriptor& d, std::size_t section0Bytes) const
{
    const std::uint64_t streamBytes = FlightPlanDescriptor::kSize + std::uint64_t{d.totalBytes};
    if (d.sectionCount == 0 || d.sectionCount > kMaxFlightPlanSections)
        return sectionsText(d.sectionCount) + ", outside 1.." + std::to_string(kMaxFlightPlanSections);
    if (d.totalBytes > m_maxPlanBytes)
        return std::to_string(d.totalBytes) + " bytes, more than the " + std::to_string(m_maxPlanBytes) +
               " this receiver holds";
    if (streamBytes < d.sectionCount || streamBytes > std::uint64_t{d.sectionCount} * FlightPlanSection::kMaxData)
        return std::to_string(d.totalBytes) + " bytes cannot make " + sectionsText(d.sectionCount) + " of 1.." +
               std::to_string(FlightPlanSection::kMaxData) + " bytes";
    if (d.sectionCount == 1 && section0Bytes != streamBytes)
        return "one section of " + std::to_string(d.totalBytes) + " plan bytes, but section 0 holds " +
               std::to_string(section0Bytes - FlightPlanDescriptor::kSize);
    return {};
}

// Takes the descriptor section 0 carries, unless it is corrupt; held
// sections beyond the count it announces are dropped.
std::optional<FlightPlanAssembler::Result> FlightPlanAssembler::adoptDescriptor(const FlightPlanDescriptor& d,
                                                                                const FlightPlanSection& section)
{
    const std::string wrong = descriptorFault(d, section.data.size());
    if (!wrong.empty())
        return failure("corrupt descriptor: " + wrong);
    m_descriptor = d;
    const auto beyond = m_sections.lower_bound(d.sectionCount);
    if (beyond == m_sections.end())
        return std::nullopt;
    const std::uint16_t first = beyond->first;
    m_sections.erase(beyond, m_sections.end());
    m_sections.emplace(section.sectionId, section.data);
    return failure("held section " + std::to_string(first) + " lies beyond the " + sectionsText(d.sectionCount) +
                   " the descriptor announces; dropped");
}

// Notes section `id` in the cycle order; true when the order says the sender
// sent sections since the previous one that are not held.
bool FlightPlanAssembler::skippedBefore(std::uint16_t id)
{
    const auto unheldIn = [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
            if (!m_sections.contains(static_cast<std::uint16_t>(k)))
                return true;
        return false;
    };
    const bool wrapped = m_lastId && id < *m_lastId;
    bool skipped = false;
    if (!m_lastId)
        skipped = unheldIn(0, id);
    else if (id > *m_lastId)
        skipped = unheldIn(*m_lastId + 1u, id);
    else if (wrapped)
        skipped = unheldIn(*m_lastId + 1u, m_descriptor ? m_descriptor->sectionCount : 0) || unheldIn(0, id);
    m_lastId = id;
    m_highestId = std::max<std::size_t>(m_highestId.value_or(0), id);
    m_wrapped = m_wrapped || wrapped;
    return skipped;
}

// All sections held: the plan, when their bytes make what the descriptor
// announces, or collecting again.
FlightPlanAssembler::Result FlightPlanAssembler::assemble()
{
    std::vector<std::uint8_t> stream;
    for (const auto& [k, data] : m_sections)
        stream.insert(stream.end(), data.begin(), data.end());
    const FlightPlanDescriptor d = *m_descriptor;
    const std::size_t expected = FlightPlanDescriptor::kSize + std::size_t{d.totalBytes};
    if (stream.size() != expected) {
        const std::size_t got = stream.size();
        restart(m_planId);
        return failure("the " + std::to_string(d.sectionCount) + " sections hold " + std::to_string(got) +
                       " bytes, not the " + std::to_string(expected) + " the descriptor announces; collecting again");
    }
    const std::span<const std::uint8_t> plan(stream.data() + FlightPlanDescriptor::kSize, d.totalBytes);
    const std::uint32_t crc = crc32(plan);
    if (crc != d.crc) {
        restart(m_planId);
        char text[64];
        std::snprintf(text, sizeof text, "CRC-32 %08X, descriptor says %08X", crc, d.crc);
        return failure(std::string(text) + "; collecting again");
    }

    Result r = progress(Result::Kind::Complete);
    r.plan.assign(plan.begin(), plan.end());
    m_lastComplete = FlightPlanAcknowledgement{m_planId, d, {}};
    restart(0);
    return r;
}

}  // namespace rcm
