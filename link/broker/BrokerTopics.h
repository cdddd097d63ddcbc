#pragma once

// The one place that names what a console says on an MQTT broker: the topics,
// per aircraft and per station, and the JSON of each report. The publisher
// (SessionPublisher), the read-only observer (BrokerObservation) and the
// fleet view all read this header, so a topic level or a field name is never
// spelled twice.
//
//   rcm/<aircraft>/station/<station>  retained  StationReport (also the will, online=false)
//   rcm/<aircraft>/frames/<station>   QoS 1     FrameReport, one per frame logged, both ways
//   rcm/<aircraft>/state/<station>    retained  StateReport, the last status received
//   rcm/<aircraft>/stats/<station>    retained  StatsReport, a LinkStatistics subset
//   rcm/<aircraft>/events/<station>   QoS 1     EventReport
//
// <aircraft> is the aircraft's ID_UA_source in the text format's form
// ("GB_133"), "unknown" until a status has said it; <station> the publishing
// console's station ID in the same form. Every topic ends with the station
// that publishes on it, so that a broker's ACL can let each station write its
// own topics only (resources/mosquitto/rcm.acl), and two stations flying one
// aircraft never overwrite each other's retained reports. Times are
// microseconds since 1970-01-01T00:00:00Z, as everywhere in the link layer.
//
// Each report goes on the broker inside a BrokerEnvelope (BrokerEnvelope.h):
// signed by its station, and sealed when the session is keyed. What follows
// is the report, the envelope's body.
//
// Every fromJson() reads what toJson() writes, exactly; it refuses a payload
// with an error that names the field ("frames: direction must be \"up\" or
// \"down\", not \"sideways\""), and ignores fields it does not know, so that a
// newer publisher's additions do not blind an older reader.

#include "codec/message/Message.h"
#include "link/framelog/FrameFacts.h"
#include "link/session/LinkStatistics.h"

#include <QByteArray>
#include <QList>
#include <QMetaType>
#include <QString>
#include <QtGlobal>

#include <optional>

// rcm/<aircraft>/station/<station>: who publishes for an aircraft, and how
// their link is. Retained, so a late subscriber sees every station at once.
struct StationReport {
    QString station;
    QString role = QStringLiteral("unknown");  // "control", "backup", "observing", "unknown"
    LinkState link = LinkState::Closed;        // JSON "closed", "waiting", "connected", "lost"
    QString description;                       // the link, for people: "UDP 127.0.0.1:5600"
    bool online = false;                       // false: gone (the will, or a graceful stop)
    qint64 utcMicros = 0;                      // when this report was made
    qint64 lastFrameUtcMicros = 0;             // last good frame from the aircraft, 0: none
    // The station in control and the backup as the aircraft last reported
    // them (ID_GCS_destination, ID_GCS_backup), text form; empty if unknown.
    QString destination;
    QString backup;

    QByteArray toJson() const;
    static std::optional<StationReport> fromJson(const QByteArray& json, QString* error);
    friend bool operator==(const StationReport&, const StationReport&) = default;
};

// rcm/<aircraft>/frames: one frame the console logged, up (sent to the
// aircraft) or down (received from it), with its bytes.
struct FrameReport {
    QString station;
    FrameDirection direction = FrameDirection::Received;  // JSON "up" (Sent), "down" (Received)
    FrameStatus status = FrameStatus::NotChecked;         // JSON frameStatusName(): "decoded" ...
    qint64 utcMicros = 0;
    std::optional<quint32> messageId;  // ID_msg when the console knew it
    // Bytes Reed-Solomon corrected per codeword, -1 beyond correction; JSON
    // [n1,n2], absent when empty (our own sends).
    QList<int> corrected;
    QByteArray bytes;  // JSON base64
    // The decoded message in the text format when the console decoded it;
    // JSON absent when empty.
    QString text;
    // Beyond the schema's minimum, so an observer's log view reads the frame
    // as the console's would: JSON "transport" ("serial", "udp", "replay",
    // "simulated"), and "enciphered" (absent when false: the bytes are plain).
    FrameTransport transport = FrameTransport::Serial;
    bool enciphered = false;
    // The publisher's frames are numbered 1, 2, 3 ... within its session (a
    // publisher's start, in UTC microseconds), one number for every frame
    // its link logged, published or not: a reader finds the frames it
    // missed by the numbers skipped. JSON "session", "seq"; absent: 0.
    qint64 session = 0;
    quint64 seq = 0;

    QByteArray toJson() const;
    static std::optional<FrameReport> fromJson(const QByteArray& json, QString* error);
    friend bool operator==(const FrameReport&, const FrameReport&) = default;
};

// rcm/<aircraft>/state: the last status received from the aircraft. Retained.
struct StateReport {
    qint64 utcMicros = 0;
    QString text;  // the message in the text format
    QString destination;
    QString backup;

    QByteArray toJson() const;
    static std::optional<StateReport> fromJson(const QByteArray& json, QString* error);
    friend bool operator==(const StateReport&, const StateReport&) = default;
};

// rcm/<aircraft>/stats: what the Overview's link health shows. Retained.
struct StatsReport {
    quint64 framesSent = 0;
    quint64 framesReceived = 0;
    quint64 refused = 0;  // all reasons together
    quint64 correctedBytesBlock1 = 0;
    quint64 correctedBytesBlock2 = 0;
    qint64 lastGoodFrameUtcMicros = 0;
    LinkState state = LinkState::Closed;  // JSON as StationReport::link

    static StatsReport of(const LinkStatistics& statistics);
    // The statistics this report can restate; the rest stay zero.
    LinkStatistics toStatistics() const;

    QByteArray toJson() const;
    static std::optional<StatsReport> fromJson(const QByteArray& json, QString* error);
    friend bool operator==(const StatsReport&, const StatsReport&) = default;
};

// rcm/<aircraft>/events: what the console's event log says.
struct EventReport {
    qint64 utcMicros = 0;
    QString severity = QStringLiteral("info");  // "info", "warning", "error", "alarm"
    QString text;
    QString station;

    QByteArray toJson() const;
    static std::optional<EventReport> fromJson(const QByteArray& json, QString* error);
    friend bool operator==(const EventReport&, const EventReport&) = default;
};

namespace BrokerTopics {

enum class Kind : quint8 { Station, Frames, State, Stats, Events };

// What a topic names: whose report of which kind, about which aircraft.
struct Topic {
    QString aircraft;
    Kind kind = Kind::Station;
    QString station;
    friend bool operator==(const Topic&, const Topic&) = default;
};

// The aircraft's name until a status has said its ID_UA_source.
inline const QString kUnknownAircraft = QStringLiteral("unknown");

inline constexpr int kStationQos = 1;
inline constexpr int kFramesQos = 1;
inline constexpr int kStateQos = 1;
inline constexpr int kStatsQos = 1;
inline constexpr int kEventsQos = 1;

// The largest payload, envelope and all, a reader takes on each kind of
// topic; a larger one is dropped before it is read, and counted. About four
// times the largest a console publishes (a sealed frame down with its text
// is under 5 KB).
qsizetype maxPayloadBytes(Kind kind);
// The largest MQTT packet a console accepts at all (MQTT 5's Maximum Packet
// Size, told the broker on connecting): the broker does not send it anything
// larger, so a huge message costs a console no memory.
inline constexpr int kMaxPacketBytes = 64 * 1024;
// Retained reports, and messages queued for an observer away, expire on the
// broker after this long (MQTT 5's message expiry): an aircraft whose
// stations stopped reporting leaves the broker by itself. A live station
// restates its report well within it (SessionPublisher).
inline constexpr int kMessageExpirySeconds = 600;

QString topic(const QString& aircraft, Kind kind, const QString& station);  // rcm/A/<kind>/S
QString stationTopic(const QString& aircraft, const QString& station);      // rcm/A/station/S
QString framesTopic(const QString& aircraft, const QString& station);       // rcm/A/frames/S
QString stateTopic(const QString& aircraft, const QString& station);        // rcm/A/state/S
QString statsTopic(const QString& aircraft, const QString& station);        // rcm/A/stats/S
QString eventsTopic(const QString& aircraft, const QString& station);       // rcm/A/events/S
QString kindName(Kind kind);                                                // "station", "frames" ...

// Subscription patterns: every station report of every aircraft (the fleet
// view), every station's frames or statistics of every aircraft, and
// everything of one aircraft (an observer).
QString allStationsPattern();                      // rcm/+/station/+
QString allPattern(Kind kind);                     // rcm/+/<kind>/+
QString aircraftPattern(const QString& aircraft);  // rcm/A/#

// Nothing for a topic outside this schema (another prefix, a kind not listed,
// an empty level, a level more or less).
std::optional<Topic> parseTopic(const QString& topic);

// A name fit to be one topic level: not empty, no '/', '+', '#' or NUL.
bool isTopicLevel(const QString& name);

// A station item of a message (ID_UA_source, ID_GCS_destination,
// ID_GCS_backup) in the text format's form, "GB_133"; empty when absent.
QString stationText(const rcm::Message& message, rcm::ItemId item);

// The JSON names of the enumerations, and back (nothing for another name).
QString linkStateName(LinkState state);  // "closed", "waiting", "connected", "lost"
std::optional<LinkState> linkStateFromName(const QString& name);
// The frame log's names (link/framelog/FrameLog.h), restated here so that
// one header says every name the broker's JSON holds.
QString frameStatusName(FrameStatus status);  // "decoded", "corrected", "uncorrectable", "rejected", "not-checked"
std::optional<FrameStatus> frameStatusFromName(const QString& name);
QString frameDirectionName(FrameDirection direction);  // "up" (Sent), "down" (Received)
std::optional<FrameDirection> frameDirectionFromName(const QString& name);
QString frameTransportName(FrameTransport transport);  // "serial", "udp", "replay", "simulated"
std::optional<FrameTransport> frameTransportFromName(const QString& name);
bool isStationRole(const QString& role);        // control, backup, observing, unknown
bool isEventSeverity(const QString& severity);  // info, warning, error, alarm

}  // namespace BrokerTopics

Q_DECLARE_METATYPE(StationReport)
Q_DECLARE_METATYPE(FrameReport)
Q_DECLARE_METATYPE(StateReport)
Q_DECLARE_METATYPE(StatsReport)
Q_DECLARE_METATYPE(EventReport)
