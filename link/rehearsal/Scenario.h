#pragma once

// A rehearsal scenario (issue 12): a JSON file naming the aircraft, the link
// and a list of timed steps - commands to set, faults to inject, a flight
// plan to upload, and expectations on what the console sees. `//` comments
// run to the end of a line. Everything is checked when the file is read, so
// that a wrong scenario is refused before anything runs, with the file, line,
// column and step of the first mistake.
//
//   "set" / "reported"   one line of the text format (codec/message/TextFormat.h),
//                        prefixed by its unit where the item is in a repeated one:
//                        "engine 2: eng_prop_pitch 140", "comms_system VHF1: Tx_freq
//                        121500", "camera 1: cam_zoom_set 40"; else the bare line.
//   "fault"              {"ber": p} every bit flips with probability p;
//                        {"outage": s} nothing passes for s seconds;
//                        {"slip": p} per frame, with probability p, 1-3 bytes are
//                        lost or added at a random place; {"burst": p} per frame,
//                        with probability p, 20-60 consecutive bytes are garbled.
//                        "direction": "up" (to the aircraft) or "down" limits it;
//                        both when absent. "clear" ends every fault.
//   "expect"             {"reported": line}, {"alarm": "link-lost" | "link-regained"},
//                        {"plan": "acknowledged"}, each with "within": s beside
//                        "expect" in the step (as docs/rehearsal.md writes it) or
//                        inside it; without "at" over the whole run:
//                        {"wrong-frames": n} (exactly n), {"frames-lost-at-most": n},
//                        {"link-lost-at-most": n} (the link-loss alarm raised at
//                        most n times: a scenario whose faults lose the link now
//                        and then says so, else each loss fails the run).

#include "codec/message/Airframe.h"
#include "codec/message/Message.h"

#include <QByteArray>
#include <QString>

#include <functional>
#include <optional>
#include <vector>

// Where a scenario is wrong: "survey.json:12:9: step 4: ...".
struct ScenarioError {
    QString file;
    int line = 0;
    int column = 0;
    int step = -1;  // 1-based step number; -1 outside the steps
    QString message;

    QString text() const;
};

// Which way a fault acts: up is console to aircraft.
enum class FaultDirection { Both, Up, Down };

struct FaultSpec {
    // CallDrop: the modem transport's satellite call is lost (NO CARRIER at
    // both ends); the console redials. In process it is an outage of
    // kCallDropOutage both ways, what the redial takes.
    enum class Kind { BitErrors, Outage, Slip, Burst, Clear, CallDrop };
    Kind kind = Kind::Clear;
    double value = 0;  // probability, or seconds for an outage
    FaultDirection direction = FaultDirection::Both;
};

struct ScenarioStep {
    enum class Kind {
        Set,
        Fault,
        Upload,
        ExpectReported,
        ExpectAlarm,
        ExpectPlan,
        ExpectWrongFrames,
        ExpectFramesLost,
        ExpectLinkLostAtMost
    };

    Kind kind = Kind::Set;
    int number = 0;  // 1-based, as people count them
    int line = 0;    // where it starts in the file
    int column = 0;
    std::optional<double> at;  // seconds of scenario time; none: over the whole run
    double within = 0;         // seconds after `at`
    QString text;              // the set or reported line, the plan's path, "link-lost" ...
    rcm::Message items;        // Set and ExpectReported: the items of the line
    FaultSpec fault;
    QByteArray plan;   // Upload: the plan's bytes
    qint64 count = 0;  // ExpectWrongFrames, ExpectFramesLost, ExpectLinkLostAtMost

    bool isExpectation() const { return kind >= Kind::ExpectReported; }
    // "step 5: expect engine 2: eng_prop_pitch 140 reported within 5 s of 0 s"
    QString describe() const;
};

struct Scenario {
    // Modem: the console dials uasim --modem through the satellite modem
    // model (SatelliteModem); at speed 1 only, its one fault call-drop.
    enum class Transport { Udp, Serial, Modem };

    // What the modem transport's model and the console's redial take: a call
    // set up in 2 s, redialled 10 s after it dropped.
    static constexpr double kModemCallSetupSeconds = 2;
    static constexpr double kCallDropOutage = 12;

    // Reads a plan file into the bytes sent (the caller chooses the reader:
    // link/plan/PlanFile.h for every format); nothing, with the reason, when it cannot.
    using PlanLoader = std::function<std::optional<QByteArray>(const QString& path, QString* error)>;

    QString path;
    QString name;
    QString airframeName;
    rcm::Airframe airframe;
    Transport transport = Transport::Udp;
    bool key = false;
    double speed = 1;
    double duration = 0;
    std::vector<ScenarioStep> steps;

    static std::optional<Scenario> load(const QString& path, const PlanLoader& loadPlan, ScenarioError* error);
    // `path` names the file in errors and is where relative paths start.
    static std::optional<Scenario> fromJson(const QByteArray& text, const QString& path, const PlanLoader& loadPlan,
                                            ScenarioError* error);
};

// The items of one "set" line for `command`: "engine 2: eng_prop_pitch 140"
// gives engine 2 with eng_prop_pitch 140 (and its key). Nothing, with the
// reason, when the line does not parse or names a unit the command lacks.
std::optional<rcm::Message> parseUnitLine(const QString& line, const rcm::Message& command, QString* error);
// Sets every item of `items` in the matching unit of `command`.
void applyItems(rcm::Message& command, const rcm::Message& items);
// True when `status` reports every item of `items` with that value.
bool reportsItems(const rcm::Message& status, const rcm::Message& items);
