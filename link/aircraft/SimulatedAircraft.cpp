#include "link/aircraft/SimulatedAircraft.h"

#include "codec/message/DigitPairs.h"
#include "codec/message/ValueCodec.h"
#include "codec/plan/PlanContents.h"

#include <algorithm>
#include <cmath>

using namespace rcm;

namespace {

constexpr auto kSurfaces = kFlapSurfaces;

// Two-bit codes the simulation acts on (PROFILE.md section 2).
constexpr unsigned kWheelOut = code::kOut, kWheelRetracted = code::kRetracted;
constexpr unsigned kFacilityEnabled = code::kEnabled, kNoDump = code::kNoDump;
constexpr unsigned kPhotoNone = code::kNone, kPhotoTake = code::kTake;

double slewRate(ItemId surface)
{
    return surface == ItemId::F_lift_set || surface == ItemId::F_airbrake_set ? SimulatedAircraft::kFlapRate
                                                                              : SimulatedAircraft::kSurfaceRate;
}

template <typename Match>
Unit* findUnit(std::vector<Unit>& units, Match match)
{
    const auto it = std::find_if(units.begin(), units.end(), match);
    return it == units.end() ? nullptr : &*it;
}

}  // namespace

SimulatedAircraft::SimulatedAircraft(Airframe airframe, std::optional<StationId> identity)
    : m_airframe(std::move(airframe)),
      m_identity(identity),
      m_commanded(restingCommand(m_airframe)),
      m_cameras(m_airframe.cameras.size())
{
}

bool SimulatedAircraft::gearMoving() const
{
    return std::any_of(m_wheels.begin(), m_wheels.end(), [](const Wheel& w) { return w.locked != w.target; });
}

void SimulatedAircraft::mergeUnit(Unit& into, const Unit& command, ApplyReport& report)
{
    const auto key = unitKey(command.kind());
    for (const ItemValue& item : command.items()) {
        if (key && item.id == *key)
            continue;
        const ItemInfo& info = itemInfo(item.id);
        const std::string where = describeUnit(command) + " " + std::string(info.name);
        if (info.kind == ValueKind::Fields) {
            const auto byte = static_cast<std::uint8_t>(item.value.number);
            for (int f = 0; f < static_cast<int>(info.fields.size()); ++f) {
                const unsigned code = fieldCode(byte, f);
                if (fieldCodeValid(info.fields[static_cast<std::size_t>(f)], code))
                    into.setFieldCode(item.id, f, code);
                else
                    report.ignored.push_back(where + " " + std::string(info.fields[static_cast<std::size_t>(f)].name) +
                                             ": code " + std::to_string(code >> 1) + std::to_string(code & 1) +
                                             " means data corruption; not acted on");
            }
        } else if (std::string reason = checkValue(info, item.value); !reason.empty()) {
            report.ignored.push_back(where + ": " + reason + "; not acted on");
        } else {
            into.set(item.id, item.value);
        }
    }
}

void SimulatedAircraft::applyHeader(const Unit& header)
{
    using enum ItemId;
    if (!m_identity)
        if (const Value* source = header.find(ID_UA_source))
            if (checkValue(itemInfo(ID_UA_source), *source).empty())
                m_identity =
                    StationId{static_cast<std::uint16_t>(source->number), static_cast<std::uint16_t>(source->second)};
    // Echoed in the status, so that the console sees its own settings came through.
    for (ItemId id : {ID_BLK12_format, ID_GCS_destination, ID_GCS_backup})
        if (const Value* v = header.find(id); v && checkValue(itemInfo(id), *v).empty())
            m_commanded.header.set(id, *v);
}

void SimulatedAircraft::applyGear(ApplyReport& report)
{
    const ItemInfo& info = itemInfo(ItemId::land_wheels);
    for (std::size_t f = 0; f < m_wheels.size(); ++f) {
        Wheel& wheel = m_wheels[f];
        const unsigned target = m_commanded.settings.fieldCode(ItemId::land_wheels, static_cast<int>(f));
        if (target == wheel.target)
            continue;
        wheel.target = target;
        report.events.push_back(std::string(info.fields[f].label) +
                                (target == kWheelRetracted ? ": retracting" : ": lowering"));
    }
}

SimulatedAircraft::ApplyReport SimulatedAircraft::apply(const Message& command)
{
    using enum ItemId;
    ApplyReport report;
    applyHeader(command.header);

    for (const Unit& engine : command.engines) {
        const Value* id = engine.find(eng_ID);
        Unit* mine =
            id ? findUnit(m_commanded.engines, [&](const Unit& u) { return u.number(eng_ID) == id->number; }) : nullptr;
        if (mine)
            mergeUnit(*mine, engine, report);
        else
            report.ignored.push_back(describeUnit(engine) + ": not fitted to this airframe; ignored");
    }
    mergeUnit(m_commanded.flaps, command.flaps, report);
    mergeUnit(m_commanded.fuelDump, command.fuelDump, report);
    mergeUnit(m_commanded.settings, command.settings, report);
    applyGear(report);

    for (const Unit& radio : command.radios) {
        const Value* id = radio.find(system_ID);
        Unit* mine =
            id ? findUnit(m_commanded.radios, [&](const Unit& u) { return u.find(system_ID)->text == id->text; })
               : nullptr;
        if (mine)
            mergeUnit(*mine, radio, report);
        else
            report.ignored.push_back(describeUnit(radio) + ": not fitted to this airframe; ignored");
    }

    if (m_airframe.senseAndAvoid)
        mergeUnit(m_commanded.sense, command.sense, report);
    else if (!command.sense.empty())
        report.ignored.push_back("sense and avoid: not fitted to this airframe; ignored");

    for (const Unit& camera : command.cameras) {
        const Value* id = camera.find(cam_ID);
        const auto it = id ? std::find_if(m_commanded.cameras.begin(), m_commanded.cameras.end(),
                                          [&](const Unit& u) { return *u.find(cam_ID) == *id; })
                           : m_commanded.cameras.end();
        if (it == m_commanded.cameras.end()) {
            report.ignored.push_back(describeUnit(camera) + ": not fitted to this airframe; ignored");
            continue;
        }
        mergeUnit(*it, camera, report);
        // A photograph on each NONE -> TAKE edge: a TAKE held over several
        // frames is one photograph, not one a second.
        Camera& state = m_cameras[static_cast<std::size_t>(it - m_commanded.cameras.begin())];
        const unsigned code = it->fieldCode(take_one_photo, 0);
        if (state.lastPhotoCode == kPhotoNone && code == kPhotoTake) {
            ++state.photos;
            state.photoSinceStatus = true;
            report.events.push_back(describeUnit(*it) + ": photograph " + std::to_string(state.photos) + " taken");
        }
        state.lastPhotoCode = code;
    }

    report.flightPlan = m_assembler.add(command.flightPlan);
    using Kind = FlightPlanAssembler::Result::Kind;
    const auto& plan = report.flightPlan;
    switch (plan.kind) {
        case Kind::Complete: {
            m_flightPlanId = plan.planId;
            m_flightPlan = plan.plan;
            m_flightPlanReport.clear();
            std::string reason;
            std::string contents;
            if (const auto decoded = rcm::plan::decode(plan.plan, &reason)) {
                const auto held = rcm::plan::Report::of(*decoded);
                contents = ": " + held.describe();
                // A format 1 plan is acknowledged as before: with its descriptor only.
                if (held.format >= 2)
                    m_flightPlanReport = held.toBytes();
            } else {
                contents = "; its contents are not a plan this aircraft reads (" + reason + ")";
            }
            report.events.push_back(
                "flight plan " + rcm::planIdText(plan.planId) + " complete: " + std::to_string(plan.plan.size()) +
                " bytes in " + std::to_string(plan.total) + (plan.total == 1 ? " section" : " sections") + contents);
            break;
        }
        case Kind::Missing: {
            std::string ids;
            for (std::uint16_t id : plan.missing)
                ids += (ids.empty() ? "" : ", ") + std::to_string(id);
            report.events.push_back("flight plan " + rcm::planIdText(plan.planId) + ": sections missing: " + ids);
            break;
        }
        case Kind::Error:
            report.ignored.push_back(plan.error);
            break;
        default:
            break;
    }
    return report;
}

void SimulatedAircraft::advance(std::chrono::milliseconds elapsed)
{
    const double seconds = std::chrono::duration<double>(elapsed).count();
    for (std::size_t i = 0; i < kSurfaces.size(); ++i) {
        const double target = static_cast<double>(m_commanded.flaps.number(kSurfaces[i]));
        const double step = slewRate(kSurfaces[i]) * seconds;
        double& angle = m_surfaceAngle[i];
        angle = angle < target ? std::min(angle + step, target) : std::max(angle - step, target);
    }
    const double travel = seconds / std::chrono::duration<double>(kGearTransit).count();
    for (Wheel& wheel : m_wheels) {
        if (wheel.target == kWheelOut)
            wheel.extension = std::min(wheel.extension + travel, 1.0);
        else if (wheel.target == kWheelRetracted)
            wheel.extension = std::max(wheel.extension - travel, 0.0);
        if (wheel.extension == 1.0)
            wheel.locked = kWheelOut;
        else if (wheel.extension == 0.0)
            wheel.locked = kWheelRetracted;
    }
}

void SimulatedAircraft::statusSent()
{
    m_statusFrames = (m_statusFrames + 1) % kMessageIdModulus;
    for (Camera& camera : m_cameras)
        camera.photoSinceStatus = false;
}

Message SimulatedAircraft::status(std::chrono::system_clock::time_point utc) const
{
    using enum ItemId;
    Message m = m_commanded;

    m.header.set(ID_msg, m_statusFrames);
    m.header.set(ID_UA_source, Value::station(identity()));
    m.header.set(time_UTC, DigitPairs::timeOf(utc).packed());
    m.header.set(date_UTC, DigitPairs::dateOf(utc).packed());

    for (std::size_t i = 0; i < kSurfaces.size(); ++i)
        m.flaps.set(kSurfaces[i], std::lround(m_surfaceAngle[i]));

    for (std::size_t f = 0; f < m_wheels.size(); ++f)
        m.settings.setFieldCode(land_wheels, static_cast<int>(f), m_wheels[f].locked);

    if (m.fuelDump.fieldCode(ENABLE_fuel_dump, 0) != kFacilityEnabled)
        for (int tank = 1; tank <= 3; ++tank)
            m.fuelDump.setFieldCode(ENABLE_fuel_dump, tank, kNoDump);

    for (std::size_t i = 0; i < m.cameras.size(); ++i)
        m.cameras[i].setFieldCode(take_one_photo, 0, m_cameras[i].photoSinceStatus ? kPhotoTake : kPhotoNone);

    if (auto ack = m_assembler.lastComplete()) {
        ack->report = m_flightPlanReport;
        m.flightPlan = ack->toSection();
    }
    return m;
}
