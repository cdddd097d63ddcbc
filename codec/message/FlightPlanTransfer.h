// A flight plan longer than one BLOCK 2 section, sent as numbered sections in
// consecutive frames and put back together by the receiver.
//
// ## Flight plan transfer (BLOCK 2)
//
// The plan. A flight plan is an opaque run of bytes (0 .. 4 GiB in principle;
// a receiver sets its own limit). It is named by its flight_plan_ID, a
// non-zero uint32 the sender chooses: a new or edited plan gets a new ID,
// because the receiver takes a section with an ID it already holds as part of
// the plan it already holds (only a section 0 whose descriptor differs from
// the one held starts that ID's plan again). A section with another ID than
// the plan being collected abandons that plan and starts collecting the new
// one. flight_plan_ID 0 with section 0 and no data (x = 0) is "no flight plan
// in this frame"; ID 0 with anything else is an error.
//
// The stream. The sender puts a 10-byte descriptor in front of the plan,
// big-endian like every number in the profile:
//
//     bytes  field
//     2      number of sections N, 1 .. 65520
//     4      total plan bytes T (descriptor not counted)
//     4      CRC-32 of the T plan bytes (IEEE 802.3 / zlib: reflected
//            polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF;
//            "123456789" gives 0xCBF43926)
//
// and cuts descriptor + plan into N sections of S data bytes each, the last
// one holding the remainder (1 .. S bytes). S is at most 215, 199 on the
// secure link, and at least 10 so that section 0 holds the whole descriptor;
// an empty plan is one section of 10 bytes. Sections are numbered from 0 in
// flight_plan_section_ID, so section 0 starts with the descriptor. The
// receiver does not need to know S: it joins the sections' data in section ID
// order, and checks that the result is 10 + T bytes long and that the CRC-32
// of the plan matches the descriptor. Every data section carries at least one
// byte.
//
// The cycle. The sender sends sections 0, 1, ... N-1, one per frame, then
// starts again at 0, until the receiver acknowledges the plan or the sender
// gives up after a number of passes. So a lost frame costs one pass, and the
// receiver knows a section is missing when a later one arrives (the IDs
// jumped) or the cycle wraps (an ID below the last one arrived; the same ID
// again is a duplicate and harmless). It keeps every section it has, so one
// pass after a loss usually completes the plan. The CRC covers the whole
// plan, so a damaged section cannot be told from the others: on a CRC
// mismatch the receiver drops all the plan's sections and collects them again
// on the next pass.
//
// Reserved section IDs. flight_plan_section_ID 0xFFF0 .. 0xFFFF never carry
// plan data; they are link control:
//
//     0xFFFF  acknowledgement, sent by the aircraft in BLOCK 2 of its status
//             frames: flight_plan_ID = the plan received complete and CRC
//             checked, data = that plan's 10-byte descriptor, echoed so that
//             the sender also knows the aircraft holds the same content,
//             then optionally up to 205 bytes of report: what the aircraft
//             understood the plan to hold, defined by the plan's format
//             (codec/plan/PlanContents.h), none for a format 1 plan. The
//             aircraft repeats it in every status frame until a later plan is
//             complete; its BLOCK 2 is empty before the first one.
//     others  reserved: a receiver ignores them.
#pragma once

#include "codec/message/Message.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rcm {

// CRC-32 (IEEE 802.3, as zlib computes it); `crc` continues a running value.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

// A flight_plan_ID as people read it, wherever it is shown: "0x5245000D"
// (docs/protocol.md's 0x%08X, the dissector's and the event log's form).
std::string planIdText(std::uint32_t planId);

inline constexpr std::uint16_t kFirstControlSectionId = 0xFFF0;
inline constexpr std::uint16_t kAcknowledgementSectionId = 0xFFFF;
inline constexpr std::size_t kMaxFlightPlanSections = kFirstControlSectionId;

struct FlightPlanDescriptor {
    static constexpr std::size_t kSize = 10;
    std::uint16_t sectionCount = 0;
    std::uint32_t totalBytes = 0;
    std::uint32_t crc = 0;

    // The first kSize bytes of `bytes`, or nothing when there are fewer.
    static std::optional<FlightPlanDescriptor> read(std::span<const std::uint8_t> bytes);
    void write(std::span<std::uint8_t, kSize> out) const;
    friend bool operator==(const FlightPlanDescriptor&, const FlightPlanDescriptor&) = default;
};

// The aircraft's "plan received" report (section ID 0xFFFF).
struct FlightPlanAcknowledgement {
    static constexpr std::size_t kMaxReport = FlightPlanSection::kMaxData - FlightPlanDescriptor::kSize;
    std::uint32_t planId = 0;
    FlightPlanDescriptor descriptor;
    std::vector<std::uint8_t> report;  // opaque here; empty when the aircraft said nothing of the contents

    FlightPlanSection toSection() const;
    // Nothing when `section` is not a well-formed acknowledgement.
    static std::optional<FlightPlanAcknowledgement> read(const FlightPlanSection& section);
    friend bool operator==(const FlightPlanAcknowledgement&, const FlightPlanAcknowledgement&) = default;
};

// The sending side: cuts a plan into sections and hands out one per frame,
// cycling until acknowledged or out of passes.
class FlightPlanUploader {
public:
    enum class State { Sending, Acknowledged, GaveUp };

    struct Progress {
        std::size_t sent = 0;   // distinct sections sent at least once
        std::size_t total = 0;  // sections in the plan
        std::size_t inPass = 0; // sections of the current pass sent
        int pass = 0;           // 1 during the first pass; 0 before the first section
        int maxPasses = 0;
    };

    // `sectionSize`: data bytes per section, FlightPlanDescriptor::kSize .. 215 (199 on the
    // secure link). `maxPasses` 0 means cycle until acknowledged.
    // Throws std::invalid_argument for a zero plan ID, a section size out of
    // range, or a plan needing more than kMaxFlightPlanSections sections.
    FlightPlanUploader(std::uint32_t planId, std::span<const std::uint8_t> plan,
                       std::size_t sectionSize = FlightPlanSection::kMaxData, int maxPasses = 3);

    std::uint32_t planId() const { return m_planId; }
    const FlightPlanDescriptor& descriptor() const { return m_descriptor; }
    const std::vector<FlightPlanSection>& sections() const { return m_sections; }
    State state() const { return m_state; }
    Progress progress() const;

    // The section for the next frame; nothing once acknowledged or given up
    // (the frame then carries an empty BLOCK 2).
    std::optional<FlightPlanSection> next();

    // Feed BLOCK 2 of every frame received from the aircraft. True when it
    // acknowledges this plan with the same descriptor; sending then stops.
    bool handleReply(const FlightPlanSection& reply);
    // What the acknowledgement said of the plan's contents (see FlightPlanAcknowledgement).
    const std::vector<std::uint8_t>& acknowledgedReport() const { return m_report; }

private:
    std::uint32_t m_planId;
    FlightPlanDescriptor m_descriptor;
    std::vector<FlightPlanSection> m_sections;
    int m_maxPasses;
    std::size_t m_next = 0;
    std::size_t m_sent = 0;
    int m_pass = 0;
    State m_state = State::Sending;
    std::vector<std::uint8_t> m_report;
};

// The receiving side: fed BLOCK 2 of every frame, says how the plan stands.
class FlightPlanAssembler {
public:
    struct Result {
        enum class Kind {
            None,             // no plan data in this frame (empty BLOCK 2 or a control section)
            InProgress,       // sections still to come
            Missing,          // still in progress, and sections were skipped: see `missing`
            Complete,         // the whole plan, CRC checked: see `plan`
            AlreadyComplete,  // a section of the plan last completed: the sender has not seen the ack yet
            Error,            // see `error`; the plan goes on being collected
        };
        Kind kind = Kind::None;
        std::uint32_t planId = 0;
        std::size_t received = 0;            // distinct sections held
        std::size_t total = 0;               // sections in the plan, 0 until section 0 arrived
        std::vector<std::uint16_t> missing;  // Missing: section IDs skipped and not held
        std::vector<std::uint8_t> plan;      // Complete: the plan bytes, descriptor removed
        std::string error;                   // Error: what was wrong, for people
    };

    // `maxPlanBytes`: descriptors announcing more are refused as corrupt.
    explicit FlightPlanAssembler(std::size_t maxPlanBytes = std::size_t{1} << 24) : m_maxPlanBytes(maxPlanBytes) {}

    Result add(const FlightPlanSection& section);

    // The acknowledgement of the plan last completed, for the aircraft's
    // status frames; its report is the caller's to add.
    std::optional<FlightPlanAcknowledgement> lastComplete() const { return m_lastComplete; }
    // The plan being collected, 0 when none.
    std::uint32_t currentPlanId() const { return m_planId; }
    void reset();

private:
    Result progress(Result::Kind kind) const;
    void restart(std::uint32_t planId);
    std::vector<std::uint16_t> unheldBelow(std::size_t end, std::uint16_t arriving) const;
    Result failure(std::string what) const;
    std::string descriptorFault(const FlightPlanDescriptor& d, std::size_t section0Bytes) const;
    std::optional<Result> adoptDescriptor(const FlightPlanDescriptor& d, const FlightPlanSection& section);
    bool skippedBefore(std::uint16_t id);
    Result assemble();

    std::size_t m_maxPlanBytes;
    std::uint32_t m_planId = 0;
    std::optional<FlightPlanDescriptor> m_descriptor;
    std::map<std::uint16_t, std::vector<std::uint8_t>> m_sections;
    std::optional<std::uint16_t> m_lastId;  // the last section ID of this plan that arrived
    std::optional<std::uint16_t> m_highestId;
    bool m_wrapped = false;  // the sender has started a pass again since we began
    std::optional<FlightPlanAcknowledgement> m_lastComplete;
};

}  // namespace rcm
