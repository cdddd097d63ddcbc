// The fleet view through one broker, for docs/performance.md: N simulated
// aircraft, each publishing as a console does at the link's real cadence,
// through one real mosquitto on loopback to one FleetFeed, FleetModel and
// FleetView (offscreen), measuring what each side costs and how late a
// report reaches its row, and accounting for every report published.
//
//   bench_fleet N [SECONDS] [WARMUP] [--no-view]
//       N aircraft (10, 100, 1000), measured for SECONDS (default 30) after
//       WARMUP seconds (default 5); prints a table and exits 0, or 1 when
//       the broker or the publishers could not be started. --no-view: the
//       FleetView is made but not shown, so nothing paints (what the feed
//       and the model cost alone).
//
// Processes apart, so that each side's CPU and memory stand alone: the
// broker (started here on a free port, with tests/support/MosquittoProcess.h), the
// publishers (this program again, with --publish: one MqttClient per
// aircraft, as each aircraft's console has its own connection, at most 250
// to a process, see runFleet), the fleet side (this process: one
// MqttClient, FleetFeed, FleetModel and a FleetView shown on the offscreen
// platform) and a frame counter (this program again, with --count-frames:
// every frame, as the observers of all the aircraft together would get
// them).
//
// Each aircraft, every second, at its own offset in the second (the fleet
// spread evenly over it): a frame up (a FrameReport of a 600-byte frame,
// base64), a frame down half a second later (with its decoded text, as a
// console publishes what it received), its station report and its link
// statistics (both retained), all QoS 1 as the console publishes them, each
// in its station's envelope, signed with its Ed25519 key. The fleet side
// trusts every station's key and verifies every message it reads: the
// station reports and the statistics (FleetFeed reads no frames). A report's
// delay runs from its envelope's number (the publisher's UTC microseconds
// when it signed it) to the model telling its views of the row (the
// dataChanged() or rowsInserted() of the model's flush).
//
// Every report is accounted for: each publisher counts what it handed to
// its client and what the broker acknowledged (PUBACK), by kind, stops on
// time and waits for the last acknowledgements; the fleet side counts the
// station reports and statistics it received and verified, the frame
// counter the frames, each aircraft's by their numbers (FrameReport::seq):
// none missing, none twice. The counts cover the whole run, not only the
// window measured.
#include "codec/message/Airframe.h"
#include "codec/message/TextFormat.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/broker/FleetFeed.h"
#include "link/broker/MqttClient.h"
#include "tests/support/MosquittoProcess.h"
#include "ui/fleet/FleetModel.h"
#include "ui/fleet/FleetView.h"

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QHash>
#include <QProcess>
#include <QRandomGenerator>
#include <QSocketNotifier>
#include <QTimer>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <set>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

namespace {

constexpr int kUsageError = 2;
constexpr qint64 kSecond = 1'000'000;
constexpr int kClientsPerProcess = 250;

qint64 utcMicros()
{
    return qint64(
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count());
}

void say(const QString& line)
{
    std::fprintf(stderr, "bench_fleet: %s\n", qPrintable(line));
}

// CPU time a process (or one of its threads: /proc/PID/task/TID) has used,
// user and system, in seconds (10 ms steps).
double cpuSeconds(const QString& statPath)
{
    QFile stat(statPath);
    if (!stat.open(QIODevice::ReadOnly))
        return -1;
    const QByteArray s = stat.readAll();
    // Fields 14 and 15 (utime, stime), counted after the parenthesised name.
    const QList<QByteArray> fields = s.mid(s.lastIndexOf(')') + 2).split(' ');
    return (fields.value(11).toDouble() + fields.value(12).toDouble()) / double(sysconf(_SC_CLK_TCK));
}

double processCpu(qint64 pid)
{
    return cpuSeconds(QStringLiteral("/proc/%1/stat").arg(pid));
}

// A line of /proc/PID/status in MiB: "VmRSS" now, "VmHWM" its peak.
double statusMiB(qint64 pid, const char* field)
{
    QFile status(QStringLiteral("/proc/%1/status").arg(pid));
    if (!status.open(QIODevice::ReadOnly))
        return -1;
    for (const QByteArray& line : status.readAll().split('\n'))
        if (line.startsWith(field) && line.size() > qsizetype(qstrlen(field)) && line[qstrlen(field)] == ':')
            return line.simplified().split(' ').value(1).toDouble() / 1024.0;
    return -1;
}

// The process ID of this process's child running `command` (its name in
// /proc/PID/stat), -1 if none: MosquittoProcess keeps its QProcess to itself.
qint64 childProcess(const QByteArray& command)
{
    const qint64 self = QCoreApplication::applicationPid();
    const QStringList entries = QDir(QStringLiteral("/proc")).entryList(QDir::Dirs | QDir::NoDotAndDotDot);
    for (const QString& entry : entries) {
        bool numeric = false;
        const qint64 pid = entry.toLongLong(&numeric);
        if (!numeric)
            continue;
        QFile stat(QStringLiteral("/proc/%1/stat").arg(pid));
        if (!stat.open(QIODevice::ReadOnly))
            continue;
        const QByteArray s = stat.readAll();
        const qsizetype open = s.indexOf('(');
        const qsizetype close = s.lastIndexOf(')');
        if (open < 0 || close < open)
            continue;
        // Field 4, the parent's ID, is the second after the name.
        const QList<QByteArray> fields = s.mid(close + 2).split(' ');
        if (s.mid(open + 1, close - open - 1) == command && fields.value(1).toLongLong() == self)
            return pid;
    }
    return -1;
}

QString aircraftName(int i)
{
    return QStringLiteral("GB_%1").arg(i + 1);
}

QString stationName(int i)
{
    return QStringLiteral("GB_%1").arg(50000 + i);
}

// Station i's signing key, the same in every process of the bench: made
// from its number (a bench's key, not a secret).
std::shared_ptr<const rcm::secure::StationSigningKey> stationKey(int i)
{
    std::array<std::uint8_t, rcm::secure::kKeySize> seed{};
    seed.fill(0x5a);
    seed[0] = std::uint8_t(i);
    seed[1] = std::uint8_t(i >> 8);
    seed[2] = std::uint8_t(i >> 16);
    return std::make_shared<const rcm::secure::StationSigningKey>(rcm::secure::SecretKey(seed));
}

// What an aircraft publishes, by kind, for the accounting.
enum Kind { kFramesUp, kFramesDown, kStation, kStats, kKinds };
const char* const kKindNames[kKinds] = {"frames up", "frames down", "station reports", "statistics"};

BrokerSettings brokerAt(quint16 port, const QString& clientId)
{
    BrokerSettings settings;
    settings.host = QStringLiteral("127.0.0.1");
    settings.port = port;
    settings.clientId = clientId;
    return settings;
}

// ---------------------------------------------------------------- publishers

// One simulated console: its connection, and what it has said so far.
struct Console {
    std::unique_ptr<MqttClient> client;
    std::unique_ptr<EnvelopeWriter> envelopes;
    QString station;
    QString framesTopic;
    QString stationTopic;
    QString statsTopic;
    QByteArray frameBytes;
    StatsReport stats;
    qint64 lastDownUtcMicros = 0;
    quint32 messageId = 0;
    qint64 session = 0;
    quint64 frameSeq = 0;
    QHash<int, int> unacknowledged;  // message ID -> Kind
};

// A frame as SessionPublisher reports it: up, our own send; down, received,
// decoded and with its text.
FrameReport frameReport(const Console& c, bool up, qint64 utcMicros, const QString& downText)
{
    FrameReport f;
    f.station = c.station;
    f.direction = up ? FrameDirection::Sent : FrameDirection::Received;
    f.status = up ? FrameStatus::NotChecked : FrameStatus::Decoded;
    f.utcMicros = utcMicros;
    f.messageId = c.messageId;
    f.bytes = c.frameBytes;
    f.transport = FrameTransport::Serial;
    f.session = c.session;
    f.seq = c.frameSeq;
    if (!up) {
        f.corrected = {0, 0};
        f.text = downText;
    }
    return f;
}

// What an aircraft publishes when, as offsets in its second.
enum class Act { FrameUp, Station, Stats, FrameDown };
struct Due {
    qint64 offsetMicros;
    int console;
    Act act;
};

// Publishes for aircraft first .. first + count - 1 of a fleet of `total`
// for `seconds`, then exits; prints "ready" once every client is connected,
// and each second the messages published so far and how late the latest of
// them went, for the fleet side to read. The fleet's seconds start on the
// UTC second, so that the processes sharing it keep one schedule.
int publish(int first, int count, int total, quint16 port, int seconds)
{
    const QString downText =
        QString::fromStdString(rcm::formatMessage(rcm::restingCommand(rcm::Airframe::wellEquipped())));
    QRandomGenerator random(133);
    std::vector<Console> consoles(static_cast<std::size_t>(count));
    int connected = 0;
    for (int k = 0; k < count; ++k) {
        const int i = first + k;
        Console& c = consoles[std::size_t(k)];
        c.client = std::make_unique<MqttClient>(brokerAt(port, QStringLiteral("bench-publisher-%1").arg(i)));
        c.station = stationName(i);
        c.envelopes = std::make_unique<EnvelopeWriter>(c.station, stationKey(i));
        c.session = utcMicros();
        c.framesTopic = BrokerTopics::framesTopic(aircraftName(i), c.station);
        c.stationTopic = BrokerTopics::stationTopic(aircraftName(i), c.station);
        c.statsTopic = BrokerTopics::statsTopic(aircraftName(i), c.station);
        c.frameBytes.resize(600);
        for (char& b : c.frameBytes)
            b = char(random.bounded(256));
        QObject::connect(c.client.get(), &MqttClient::connected, [&connected] { ++connected; });
        QObject::connect(c.client.get(), &MqttClient::errorOccurred,
                         [](const QString& error) { say(QStringLiteral("publisher: ") + error); });
        c.client->start();
    }
    QElapsedTimer waited;
    waited.start();
    qint64 told = 0;
    while (connected < count) {
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
        if (waited.elapsed() - told >= 5000) {
            told = waited.elapsed();
            say(QStringLiteral("publisher: %1 of %2 clients connected after %3 s")
                    .arg(connected)
                    .arg(count)
                    .arg(told / 1000));
        }
        if (waited.elapsed() > 60'000) {
            say(QStringLiteral("publisher: %1 of %2 clients connected after 60 s").arg(connected).arg(count));
            return 1;
        }
    }
    if (first == 0)
        say(QStringLiteral("a frame's envelope is %1 bytes up, %2 bytes down")
                .arg(consoles[0]
                         .envelopes
                         ->wrap(consoles[0].framesTopic, frameReport(consoles[0], true, utcMicros(), downText).toJson())
                         .size())
                .arg(
                    consoles[0]
                        .envelopes
                        ->wrap(consoles[0].framesTopic, frameReport(consoles[0], false, utcMicros(), downText).toJson())
                        .size()));
    std::printf("ready\n");
    std::fflush(stdout);

    std::vector<Due> plan;
    plan.reserve(std::size_t(count) * 4);
    for (int k = 0; k < count; ++k) {
        const qint64 offset = qint64(first + k) * kSecond / total;
        plan.push_back({offset, k, Act::FrameUp});
        plan.push_back({(offset + 100'000) % kSecond, k, Act::Station});
        plan.push_back({(offset + 200'000) % kSecond, k, Act::Stats});
        plan.push_back({(offset + 500'000) % kSecond, k, Act::FrameDown});
    }
    std::sort(plan.begin(), plan.end(), [](const Due& a, const Due& b) { return a.offsetMicros < b.offsetMicros; });

    quint64 published = 0;
    quint64 refused = 0;
    qint64 lateMaxMicros = 0;
    std::array<quint64, kKinds> handed{};
    std::array<quint64, kKinds> acknowledged{};
    for (Console& c : consoles)
        QObject::connect(c.client.get(), &MqttClient::published, [&c, &acknowledged](int id) {
            const auto it = c.unacknowledged.constFind(id);
            if (it == c.unacknowledged.cend())
                return;
            ++acknowledged[std::size_t(*it)];
            c.unacknowledged.erase(it);
        });
    const auto send = [](Console& c, const QString& topic, const QByteArray& body, bool retain, int kind) {
        int id = 0;
        const bool ok = c.client->publish(topic, c.envelopes->wrap(topic, body), 1, retain, &id,
                                          BrokerTopics::kMessageExpirySeconds);
        if (ok)
            c.unacknowledged.insert(id, kind);
        return ok;
    };
    std::size_t next = 0;
    const qint64 begin = (utcMicros() / kSecond + 1) * kSecond;
    qint64 cycleStart = begin;
    const auto act = [&](const Due& due) {
        Console& c = consoles[std::size_t(due.console)];
        const QString& station = c.station;
        const qint64 now = utcMicros();
        bool ok = false;
        switch (due.act) {
            case Act::FrameUp:
            case Act::FrameDown: {
                const bool up = due.act == Act::FrameUp;
                ++c.frameSeq;
                const FrameReport f = frameReport(c, up, now, downText);
                if (up) {
                    ++c.messageId;
                    ++c.stats.framesSent;
                } else {
                    c.lastDownUtcMicros = now;
                    ++c.stats.framesReceived;
                }
                ok = send(c, c.framesTopic, f.toJson(), false, up ? kFramesUp : kFramesDown);
                if (ok)
                    ++handed[up ? kFramesUp : kFramesDown];
                break;
            }
            case Act::Station: {
                StationReport r;
                r.station = station;
                r.role = QStringLiteral("control");
                r.link = LinkState::Connected;
                r.description = QStringLiteral("serial /dev/ttyUSB0 9600 8N1");
                r.online = true;
                r.utcMicros = now;
                r.lastFrameUtcMicros = c.lastDownUtcMicros;
                r.destination = station;
                ok = send(c, c.stationTopic, r.toJson(), true, kStation);
                if (ok)
                    ++handed[kStation];
                break;
            }
            case Act::Stats:
                c.stats.lastGoodFrameUtcMicros = c.lastDownUtcMicros;
                c.stats.state = LinkState::Connected;
                ok = send(c, c.statsTopic, c.stats.toJson(), true, kStats);
                if (ok)
                    ++handed[kStats];
                break;
        }
        ++(ok ? published : refused);
    };
    QTimer ticker;
    ticker.setTimerType(Qt::PreciseTimer);
    ticker.setInterval(2);
    int reportedSecond = 0;
    QObject::connect(&ticker, &QTimer::timeout, [&] {
        const qint64 now = utcMicros();
        while (!plan.empty()) {
            if (next == plan.size()) {
                next = 0;
                cycleStart += kSecond;
            }
            const qint64 due = cycleStart + plan[next].offsetMicros;
            if (due > now)
                break;
            lateMaxMicros = std::max(lateMaxMicros, now - due);
            act(plan[next++]);
        }
        if (now > begin && (now - begin) / kSecond > reportedSecond) {
            reportedSecond = int((now - begin) / kSecond);
            std::printf("second %d published %llu refused %llu late_max_us %lld\n", reportedSecond,
                        static_cast<unsigned long long>(published), static_cast<unsigned long long>(refused),
                        static_cast<long long>(lateMaxMicros));
            std::fflush(stdout);
            lateMaxMicros = 0;
            if (reportedSecond >= seconds)
                QCoreApplication::quit();
        }
    });
    ticker.start();
    QCoreApplication::exec();
    ticker.stop();
    // The last acknowledgements, then what was handed and acknowledged, by kind.
    QElapsedTimer draining;
    draining.start();
    const auto waiting = [&] {
        std::size_t n = 0;
        for (const Console& c : consoles)
            n += std::size_t(c.unacknowledged.size());
        return n;
    };
    while (waiting() > 0 && draining.elapsed() < 30'000)
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
    std::printf("totals");
    for (int k = 0; k < kKinds; ++k)
        std::printf(" %llu %llu", static_cast<unsigned long long>(handed[std::size_t(k)]),
                    static_cast<unsigned long long>(acknowledged[std::size_t(k)]));
    std::printf(" unacknowledged %zu\n", waiting());
    std::fflush(stdout);
    for (Console& c : consoles)
        c.client->stop();
    return 0;
}

// ---------------------------------------------------------------- frame counter

// Every frame the broker delivers to a subscriber of rcm/+/frames/+, as an
// observer of each aircraft would get it: counted by direction, and each
// aircraft's frame numbers kept, so that a number never seen is a frame lost
// on the way and one seen twice came twice. Prints "ready" once subscribed;
// on "report" from the fleet side, waits until nothing came for 2 s, prints
// "frames UP DOWN TWICE SKIPPED" and exits. The envelopes are read, not
// verified: this is the bench's ledger, not a console (the fleet side
// verifies what it shows).
int countFrames(quint16 port)
{
    MqttClient client(brokerAt(port, QStringLiteral("bench-frame-counter")));
    QHash<QString, std::set<quint64>> numbers;
    quint64 up = 0, down = 0, twice = 0;
    qint64 last = utcMicros();
    QObject::connect(&client, &MqttClient::messageReceived, [&](const QString& topic, const QByteArray& payload) {
        last = utcMicros();
        const std::optional<BrokerEnvelope> e = BrokerEnvelope::fromJson(payload, nullptr);
        const std::optional<FrameReport> f = e ? FrameReport::fromJson(e->body, nullptr) : std::nullopt;
        if (!f)
            return;
        ++(f->direction == FrameDirection::Sent ? up : down);
        if (!numbers[topic].insert(f->seq).second)
            ++twice;
    });
    QObject::connect(&client, &MqttClient::subscribed, [] {
        std::printf("ready\n");
        std::fflush(stdout);
    });
    client.subscribe(BrokerTopics::allPattern(BrokerTopics::Kind::Frames), BrokerTopics::kFramesQos);
    client.start();
    QSocketNotifier input(STDIN_FILENO, QSocketNotifier::Read);
    bool reporting = false;
    QObject::connect(&input, &QSocketNotifier::activated, [&] {
        char line[64];
        if (!std::fgets(line, sizeof line, stdin) || qstrncmp(line, "report", 6) == 0)
            reporting = true;
    });
    QTimer tick;
    tick.setInterval(100);
    QObject::connect(&tick, &QTimer::timeout, [&] {
        if (!reporting || utcMicros() - last < 2 * kSecond)
            return;
        quint64 skipped = 0;
        for (const std::set<quint64>& seen : std::as_const(numbers))
            if (!seen.empty())
                skipped += *seen.rbegin() - *seen.begin() + 1 - quint64(seen.size());
        std::printf("frames %llu %llu %llu %llu\n", static_cast<unsigned long long>(up),
                    static_cast<unsigned long long>(down), static_cast<unsigned long long>(twice),
                    static_cast<unsigned long long>(skipped));
        std::fflush(stdout);
        QCoreApplication::quit();
    });
    tick.start();
    QCoreApplication::exec();
    client.stop();
    return 0;
}

// ---------------------------------------------------------------- fleet side

struct Snapshot {
    qint64 steadyMicros = 0;
    double brokerCpu = 0;
    double publishersCpu = 0;
    double fleetCpu = 0;
    double fleetGuiCpu = 0;
    double counterCpu = 0;
    quint64 statsReported = 0;
    quint64 published = 0;
};

// What the publishers said last ("second S published P refused R late_max_us L"),
// and at their end ("totals", then handed and acknowledged of each kind).
struct PublisherLine {
    int second = 0;
    quint64 published = 0;
    quint64 refused = 0;
    qint64 lateMaxMicros = 0;
    bool done = false;
    std::array<quint64, kKinds> handed{};
    std::array<quint64, kKinds> acknowledged{};
    quint64 unacknowledged = 0;
};

int runFleet(int n, int seconds, int warmup, bool shown)
{
    // A client that falls behind has 20,000 messages queued for it before the
    // broker drops any (mosquitto's default: 1,000); the broker says how many
    // it dropped in $SYS, once a second.
    rcm::test::MosquittoProcess::Options brokerOptions;
    brokerOptions.more = {QStringLiteral("max_queued_messages 20000"), QStringLiteral("sys_interval 1")};
    rcm::test::MosquittoProcess broker(brokerOptions);
    if (!broker.start()) {
        say(QStringLiteral("cannot start /usr/sbin/mosquitto: ") + broker.setupError());
        return 1;
    }
    QElapsedTimer waited;
    waited.start();
    while (!broker.accepts()) {
        if (waited.elapsed() > 10'000) {
            say(QStringLiteral("mosquitto does not listen: ") + QString::fromLocal8Bit(broker.stderrText()));
            return 1;
        }
    }
    const qint64 mosquittoPid = childProcess("mosquitto");
    if (mosquittoPid <= 0) {
        say(QStringLiteral("cannot find mosquitto among this process's children"));
        return 1;
    }

    MqttClient fleetClient(brokerAt(broker.port(), QStringLiteral("bench-fleet")));
    FleetFeed feed(&fleetClient);
    auto trust = std::make_shared<BrokerTrust>();
    for (int i = 0; i < n; ++i)
        trust->trustStation(stationName(i), stationKey(i)->publicKey());
    feed.setTrust(trust);
    // Everything the broker delivered, by kind, as the client judged it.
    std::array<quint64, kKinds> delivered{};
    quint64 deliveredRefused = 0;
    qint64 lastDelivery = 0;
    QObject::connect(&fleetClient, &MqttClient::messageOpened, [&](const OpenedMessage& m) {
        lastDelivery = utcMicros();
        if (m.refused() || !m.verified()) {
            ++deliveredRefused;
            if (deliveredRefused <= 3)
                say(QStringLiteral("refused or unverified: ") + m.refusal);
            return;
        }
        if (m.where->kind == BrokerTopics::Kind::Station)
            ++delivered[kStation];
        else if (m.where->kind == BrokerTopics::Kind::Stats)
            ++delivered[kStats];
    });
    FleetModel model;
    QObject::connect(&feed, &FleetFeed::aircraftUpdated, &model, &FleetModel::update);
    FleetView view(&model);
    view.setBroker(QStringLiteral("mqtt://127.0.0.1:%1").arg(broker.port()));
    QObject::connect(&fleetClient, &MqttClient::connected, &view, [&view] { view.setBrokerConnected(true); });
    view.resize(1000, 700);
    if (shown)
        view.show();

    // Statistics reported since the model's last flush, by when they were
    // published (their envelope's number, the publisher's UTC microseconds);
    // the flush is the model's dataChanged() without roles, or
    // rowsInserted() (refreshAges() names its roles).
    bool measuring = false;
    quint64 statsReported = 0;
    std::vector<qint64> waiting;
    std::vector<std::int64_t> delays;
    delays.reserve(std::size_t(n) * std::size_t(seconds) + 1024);
    QObject::connect(&feed, &FleetFeed::statsReported, [&](const QString&, const StatsReport&, qint64 published) {
        ++statsReported;
        if (measuring)
            waiting.push_back(published);
    });
    const auto told = [&] {
        if (waiting.empty())
            return;
        const qint64 now = utcMicros();
        for (qint64 sent : waiting)
            delays.push_back(now - sent);
        waiting.clear();
    };
    QObject::connect(&model, &QAbstractItemModel::rowsInserted, told);
    QObject::connect(&model, &QAbstractItemModel::dataChanged,
                     [&](const QModelIndex&, const QModelIndex&, const QList<int>& roles) {
                         if (roles.isEmpty())
                             told();
                     });
    fleetClient.start();
    MqttClient sysClient(brokerAt(broker.port(), QStringLiteral("bench-sys")));
    quint64 brokerDropped = 0;
    QObject::connect(&sysClient, &MqttClient::messageReceived,
                     [&](const QString&, const QByteArray& payload) { brokerDropped = payload.toULongLong(); });
    sysClient.subscribe(QStringLiteral("$SYS/broker/publish/messages/dropped"), 0);
    sysClient.start();

    // The frames' ledger, a process of its own, subscribed before anyone publishes.
    QProcess counter;
    counter.setProgram(QCoreApplication::applicationFilePath());
    counter.setArguments({QStringLiteral("--count-frames"), QString::number(broker.port())});
    counter.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    bool counterReady = false;
    QList<QByteArray> counted;
    QObject::connect(&counter, &QProcess::readyReadStandardOutput, [&] {
        while (counter.canReadLine()) {
            const QByteArray line = counter.readLine().trimmed();
            if (line == "ready")
                counterReady = true;
            else if (line.startsWith("frames "))
                counted = line.split(' ');
        }
    });
    counter.start();
    waited.restart();
    while (!counterReady) {
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
        if (counter.state() == QProcess::NotRunning || waited.elapsed() > 30'000) {
            say(QStringLiteral("the frame counter did not get ready"));
            return 1;
        }
    }

    // The publishers, in processes of at most kClientsPerProcess clients:
    // libmosquitto's network loop waits with select(), which cannot watch a
    // descriptor above 1023, and each client holds three (its socket and
    // the loop's wake-up pair): about 340 clients is all one process holds.
    const int processes = (n + kClientsPerProcess - 1) / kClientsPerProcess;
    std::vector<std::unique_ptr<QProcess>> publishers;
    std::vector<PublisherLine> lines(static_cast<std::size_t>(processes));
    int ready = 0;
    for (int p = 0; p < processes; ++p) {
        const int first = p * n / processes;
        const int count = (p + 1) * n / processes - first;
        auto process = std::make_unique<QProcess>();
        QProcess* raw = process.get();
        raw->setProgram(QCoreApplication::applicationFilePath());
        raw->setArguments({QStringLiteral("--publish"), QString::number(first), QString::number(count),
                           QString::number(n), QString::number(broker.port()), QString::number(warmup + seconds + 2)});
        raw->setProcessChannelMode(QProcess::ForwardedErrorChannel);
        PublisherLine& last = lines[std::size_t(p)];
        QObject::connect(raw, &QProcess::readyReadStandardOutput, [raw, &last, &ready] {
            while (raw->canReadLine()) {
                const QByteArray line = raw->readLine().trimmed();
                if (line == "ready") {
                    ++ready;
                    continue;
                }
                const QList<QByteArray> f = line.split(' ');
                if (f.size() == 2 + 2 * kKinds + 1 && f[0] == "totals") {
                    for (int k = 0; k < kKinds; ++k) {
                        last.handed[std::size_t(k)] = f[1 + 2 * k].toULongLong();
                        last.acknowledged[std::size_t(k)] = f[2 + 2 * k].toULongLong();
                    }
                    last.unacknowledged = f.last().toULongLong();
                    last.done = true;
                    continue;
                }
                if (f.size() == 8 && f[0] == "second") {
                    last.second = f[1].toInt();
                    last.published = f[3].toULongLong();
                    last.refused = f[5].toULongLong();
                    last.lateMaxMicros = std::max(last.lateMaxMicros, f[7].toLongLong());
                }
            }
        });
        raw->start();
        if (!raw->waitForStarted()) {
            say(QStringLiteral("cannot start the publishers: ") + raw->errorString());
            return 1;
        }
        publishers.push_back(std::move(process));
    }
    waited.restart();
    while (ready < processes) {
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
        const bool ended = std::any_of(publishers.begin(), publishers.end(),
                                       [](const auto& p) { return p->state() == QProcess::NotRunning; });
        if (ended || waited.elapsed() > 90'000) {
            say(QStringLiteral("the publishers did not get ready"));
            return 1;
        }
    }
    const qint64 fleetPid = QCoreApplication::applicationPid();
    say(QStringLiteral("%1 aircraft connected in %2 ms (%3 publisher processes); warming up %4 s, then measuring %5 s")
            .arg(n)
            .arg(waited.elapsed())
            .arg(processes)
            .arg(warmup)
            .arg(seconds));
    const auto publishersCpu = [&] {
        double total = 0;
        for (const auto& p : publishers)
            total += processCpu(p->processId());
        return total;
    };
    const auto publishersRssNow = [&] {
        double total = 0;
        for (const auto& p : publishers)
            total += statusMiB(p->processId(), "VmRSS");
        return total;
    };
    const auto publishedSoFar = [&] {
        quint64 total = 0;
        for (const PublisherLine& l : lines)
            total += l.published;
        return total;
    };

    QElapsedTimer steady;
    steady.start();
    const auto snapshot = [&] {
        Snapshot s;
        s.steadyMicros = steady.nsecsElapsed() / 1000;
        s.brokerCpu = processCpu(mosquittoPid);
        s.publishersCpu = publishersCpu();
        s.fleetCpu = processCpu(fleetPid);
        s.fleetGuiCpu = cpuSeconds(QStringLiteral("/proc/%1/task/%1/stat").arg(fleetPid));
        s.counterCpu = processCpu(counter.processId());
        s.statsReported = statsReported;
        s.published = publishedSoFar();
        return s;
    };
    Snapshot start, end;
    double brokerRss = 0, publishersRss = 0, fleetRss = 0, counterRss = 0;
    QEventLoop loop;
    QTimer::singleShot(warmup * 1000, Qt::PreciseTimer, &loop, [&] {
        start = snapshot();
        for (PublisherLine& l : lines)
            l.lateMaxMicros = 0;
        measuring = true;
    });
    QTimer::singleShot((warmup + seconds) * 1000, Qt::PreciseTimer, &loop, [&] {
        end = snapshot();
        measuring = false;
        brokerRss = statusMiB(mosquittoPid, "VmRSS");
        publishersRss = publishersRssNow();
        fleetRss = statusMiB(fleetPid, "VmRSS");
        counterRss = statusMiB(counter.processId(), "VmRSS");
        loop.quit();
    });
    loop.exec();

    quint64 refusedByClients = 0;
    qint64 lateMaxMicros = 0;
    for (const PublisherLine& l : lines) {
        refusedByClients += l.refused;
        lateMaxMicros = std::max(lateMaxMicros, l.lateMaxMicros);
    }
    const double wall = double(end.steadyMicros - start.steadyMicros) / 1e6;
    const auto percent = [&](double a, double b) { return 100.0 * (b - a) / wall; };
    // One statistics message a second for each aircraft, over the time measured.
    const quint64 expected = quint64(double(n) * wall + 0.5);
    const quint64 reported = end.statsReported - start.statsReported;
    std::sort(delays.begin(), delays.end());
    const auto at = [&](double q) {
        return delays.empty() ? 0.0 : double(delays[std::size_t(q * double(delays.size() - 1))]) / 1000.0;
    };

    std::printf("\nbench_fleet: %d aircraft through one mosquitto, %.1f s measured after %d s warm-up\n", n, wall,
                warmup);
    std::printf(
        "messages published: %llu in the window (%.0f/s; %llu refused by the client); publishers at most "
        "%.1f ms late on their schedule\n",
        static_cast<unsigned long long>(end.published - start.published),
        double(end.published - start.published) / wall, static_cast<unsigned long long>(refusedByClients),
        double(lateMaxMicros) / 1000.0);
    std::printf("statistics reported to the fleet in the window: %llu, %llu due (%.2f %%)\n",
                static_cast<unsigned long long>(reported), static_cast<unsigned long long>(expected),
                expected ? 100.0 * double(reported) / double(expected) : 0.0);
    std::printf("rows: %d\n\n", model.rowCount());
    std::printf("| process | CPU (%% of one core) | RSS (MiB) |\n|---|---:|---:|\n");
    std::printf("| mosquitto | %.1f | %.1f |\n", percent(start.brokerCpu, end.brokerCpu), brokerRss);
    std::printf("| publishers (%d MqttClients in %d processes) | %.1f | %.1f |\n", n, processes,
                percent(start.publishersCpu, end.publishersCpu), publishersRss);
    std::printf("| fleet side (MqttClient, FleetFeed, FleetModel%s) | %.1f | %.1f |\n",
                shown ? ", FleetView shown" : ", no view shown", percent(start.fleetCpu, end.fleetCpu), fleetRss);
    std::printf("| of which its GUI thread | %.1f | |\n", percent(start.fleetGuiCpu, end.fleetGuiCpu));
    std::printf("| frame counter (one MqttClient reading every frame's envelope) | %.1f | %.1f |\n\n",
                percent(start.counterCpu, end.counterCpu), counterRss);
    std::printf("statistics to row: n=%zu  median %.1f ms  p99 %.1f ms  max %.1f ms\n", delays.size(), at(0.5),
                at(0.99), delays.empty() ? 0.0 : double(delays.back()) / 1000.0);

    // Every report of the whole run: the publishers stop on time and wait
    // for their last acknowledgements; then the fleet side waits until
    // nothing more comes (2 s of quiet) and counts.
    QElapsedTimer settling;
    settling.start();
    while (settling.elapsed() < 120'000) {
        const bool allDone = std::all_of(lines.begin(), lines.end(), [](const PublisherLine& l) { return l.done; }) &&
                             std::all_of(publishers.begin(), publishers.end(),
                                         [](const auto& p) { return p->state() == QProcess::NotRunning; });
        if (allDone && utcMicros() - lastDelivery > 2 * kSecond)
            break;
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
    }
    counter.write("report\n");
    while (counted.isEmpty() && counter.state() != QProcess::NotRunning && settling.elapsed() < 180'000)
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 100);
    std::array<quint64, kKinds> handed{};
    std::array<quint64, kKinds> acknowledged{};
    quint64 unacknowledged = 0;
    for (const PublisherLine& l : lines) {
        for (int k = 0; k < kKinds; ++k) {
            handed[std::size_t(k)] += l.handed[std::size_t(k)];
            acknowledged[std::size_t(k)] += l.acknowledged[std::size_t(k)];
        }
        unacknowledged += l.unacknowledged;
    }
    quint64 framesTwice = 0, gaps = 0;
    if (counted.size() == 5) {
        delivered[kFramesUp] = counted[1].toULongLong();
        delivered[kFramesDown] = counted[2].toULongLong();
        framesTwice = counted[3].toULongLong();
        gaps = counted[4].toULongLong();
    } else {
        say(QStringLiteral("the frame counter said nothing"));
    }
    std::printf(
        "\nevery report of the run (publishers' counts; the fleet side's for station reports and "
        "statistics, verified; the frame counter's for frames):\n\n");
    std::printf(
        "| report | handed to the client | acknowledged by the broker | received | "
        "missing |\n|---|---:|---:|---:|---:|\n");
    quint64 missingTotal = 0;
    for (int k = 0; k < kKinds; ++k) {
        const quint64 a = acknowledged[std::size_t(k)];
        const quint64 d = delivered[std::size_t(k)];
        const quint64 missing = a > d ? a - d : 0;
        missingTotal += missing;
        std::printf("| %s | %llu | %llu | %llu | %llu |\n", kKindNames[k],
                    static_cast<unsigned long long>(handed[std::size_t(k)]), static_cast<unsigned long long>(a),
                    static_cast<unsigned long long>(d), static_cast<unsigned long long>(missing));
    }
    std::printf(
        "\nnot acknowledged at the end: %llu; refused or unverified at the fleet: %llu; frames seen twice: "
        "%llu; frame numbers skipped: %llu; reports missing: %llu; dropped by the broker (a subscriber's "
        "queue full): %llu\n",
        static_cast<unsigned long long>(unacknowledged), static_cast<unsigned long long>(deliveredRefused),
        static_cast<unsigned long long>(framesTwice), static_cast<unsigned long long>(gaps),
        static_cast<unsigned long long>(missingTotal), static_cast<unsigned long long>(brokerDropped));

    for (const auto& p : publishers) {
        p->kill();
        p->waitForFinished();
    }
    counter.kill();
    counter.waitForFinished();
    sysClient.stop();
    fleetClient.stop();
    broker.stop();
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc == 3 && qstrcmp(argv[1], "--count-frames") == 0) {
        // --count-frames PORT: started by the fleet side.
        QCoreApplication app(argc, argv);
        return countFrames(quint16(QByteArray(argv[2]).toInt()));
    }
    if (argc >= 2 && qstrcmp(argv[1], "--publish") == 0) {
        // --publish FIRST COUNT TOTAL PORT SECONDS: started by the fleet side.
        QCoreApplication app(argc, argv);
        if (argc != 7)
            return kUsageError;
        const auto number = [&](int i) { return QByteArray(argv[i]).toInt(); };
        return publish(number(2), number(3), number(4), quint16(number(5)), number(6));
    }
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
        qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    QStringList args = app.arguments().mid(1);
    const bool shown = !args.removeAll(QStringLiteral("--no-view"));
    bool ok = !args.isEmpty();
    const int n = ok ? args[0].toInt(&ok) : 0;
    const int seconds = args.size() >= 2 ? args[1].toInt() : 30;
    const int warmup = args.size() >= 3 ? args[2].toInt() : 5;
    if (!ok || n < 1 || seconds < 1 || warmup < 0 || args.size() > 3) {
        std::fprintf(stderr,
                     "usage: bench_fleet N [SECONDS] [WARMUP] [--no-view]   (N aircraft, e.g. 10, 100, 1000)\n");
        return kUsageError;
    }
    return runFleet(n, seconds, warmup, shown);
}
