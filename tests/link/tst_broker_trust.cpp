// Trust on the broker (docs/security.md, "The broker"): every message a
// console publishes signed by its station and, when the link is keyed,
// sealed; observers and the fleet believing only what a trusted key signed;
// messages larger than any console publishes dropped before they are read;
// nothing missed silently over a broker's restart; TLS and credentials that
// fail said so. Against the real mosquitto (the tests' configuration, and
// the deployment one in resources/mosquitto/), with the real mosquitto_pub
// as whoever else is on the broker.

#include "codec/receive/LoggedFrameReading.h"
#include "codec/secure/BrokerSeal.h"
#include "codec/secure/StationSigningKey.h"
#include "link/broker/BrokerEnvelope.h"
#include "link/broker/BrokerObservation.h"
#include "link/broker/BrokerSettings.h"
#include "link/broker/BrokerTopics.h"
#include "link/broker/BrokerTrust.h"
#include "link/broker/EnvelopeWriter.h"
#include "link/broker/MqttClient.h"
#include "link/broker/SequenceCheck.h"
#include "link/broker/SessionPublisher.h"
#include "link/clock/VirtualClock.h"
#include "link/eventlog/EventLog.h"
#include "link/session/ConsoleSession.h"
#include "link/session/LinkEvents.h"
#include "link/session/LinkSettings.h"
#include "ui/alerts/ConsoleAlerts.h"
#include "ui/alerts/ErrorBanner.h"
#include "codec/frame/Frame.h"
#include "codec/message/Airframe.h"
#include "codec/message/ItemTable.h"
#include "ui/panels/CommandState.h"
#include "ui/window/LinkSettingsWidget.h"
#include "ui/window/MainWindow.h"

#include "MosquittoProcess.h"
#include "RunProgram.h"
#include "TcpRelay.h"

#include <QApplication>
#include <QFile>
#include <QProcess>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUdpSocket>

#include <memory>
#include <set>

using rcm::test::MosquittoProcess;
using rcm::test::TcpRelay;

namespace {

constexpr int kTimeoutMs = 10000;
// A broker stopped and started again: the clients retry 1 s, 2 s, 3 s ...
constexpr int kRejoinTimeoutMs = 25000;
constexpr qint64 kT0 = 1764000000000000;  // 2025-11-24T16:00:00Z

const QString kAircraft = QStringLiteral("GB_133");
const QString kPrimary = QStringLiteral("GB_30226");

BrokerSettings local(quint16 port)
{
    BrokerSettings s;
    s.host = QStringLiteral("127.0.0.1");
    s.port = port;
    return s;
}

std::shared_ptr<const rcm::secure::StationSigningKey> stationKey(const QString& station)
{
    static QHash<QString, std::shared_ptr<const rcm::secure::StationSigningKey>> keys;
    auto& key = keys[station];
    if (!key)
        key = std::make_shared<const rcm::secure::StationSigningKey>(rcm::secure::StationSigningKey::generate());
    return key;
}

EnvelopeWriter signedAs(const QString& station)
{
    return EnvelopeWriter(station, stationKey(station));
}

std::shared_ptr<BrokerTrust> trusting(const QStringList& stations)
{
    auto trust = std::make_shared<BrokerTrust>();
    for (const QString& station : stations)
        trust->trustStation(station, stationKey(station)->publicKey());
    return trust;
}

BrokerSettings observing(quint16 port, std::shared_ptr<const BrokerTrust> trust)
{
    BrokerSettings s = local(port);
    s.aircraft = kAircraft;
    s.trust = std::move(trust);
    return s;
}

QByteArray frameBytes(int seed)
{
    QByteArray b(510, '\0');
    for (int i = 0; i < b.size(); ++i)
        b[i] = char((seed * 31 + i) & 0xFF);
    return b;
}

LoggedFrame sentFrame(int i)
{
    LoggedFrame f;
    f.entry.utcMicros = kT0 + qint64(i) * 1'000'000;
    f.entry.direction = FrameDirection::Sent;
    f.entry.transport = FrameTransport::Udp;
    f.entry.status = FrameStatus::NotChecked;
    f.entry.offset = -1;
    f.entry.length = 510;
    f.messageId = quint32(i);
    f.bytes = frameBytes(i);
    return f;
}

// mosquitto_pub, as anyone on the broker runs it: QoS 1. Its exit status, or -1.
int runMosquittoPub(QStringList args, quint16 port, const QString& topic, bool retain)
{
    args << QStringLiteral("-h") << QStringLiteral("127.0.0.1") << QStringLiteral("-p") << QString::number(port)
         << QStringLiteral("-t") << topic << QStringLiteral("-q") << QStringLiteral("1");
    if (retain)
        args << QStringLiteral("-r");
    QProcess p;
    p.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    p.start(QStringLiteral("mosquitto_pub"), args);
    if (!p.waitForFinished(60000) || p.exitStatus() != QProcess::NormalExit)
        return -1;
    return p.exitCode();
}

int mosquittoPub(quint16 port, const QString& topic, const QByteArray& message, bool retain,
                 const QStringList& more = {})
{
    return runMosquittoPub(more + QStringList{QStringLiteral("-m"), QString::fromUtf8(message)}, port, topic, retain);
}

// A message of `mebibytes` MiB, from a file written a MiB at a time: this
// process never holds it.
int mosquittoPubHuge(quint16 port, const QString& topic, int mebibytes, bool retain, const QStringList& more = {})
{
    QTemporaryDir dir;
    QFile file(dir.filePath(QStringLiteral("huge")));
    if (!file.open(QIODevice::WriteOnly))
        return -1;
    const QByteArray mebibyte(1024 * 1024, 'x');
    for (int i = 0; i < mebibytes; ++i)
        if (file.write(mebibyte) != mebibyte.size())
            return -1;
    file.close();
    return runMosquittoPub(more + QStringList{QStringLiteral("-f"), file.fileName()}, port, topic, retain);
}

// A line of /proc/self/status in KiB ("VmRSS", "VmHWM").
qint64 statusKiB(const char* field)
{
    QFile status(QStringLiteral("/proc/self/status"));
    if (!status.open(QIODevice::ReadOnly))
        return -1;
    for (const QByteArray& line : status.readAll().split('\n'))
        if (line.startsWith(field) && line.size() > qsizetype(qstrlen(field)) && line[qstrlen(field)] == ':')
            return line.simplified().split(' ').value(1).toLongLong();
    return -1;
}

// VmHWM starts again from VmRSS (Linux: /proc/PID/clear_refs, 5).
bool resetPeak()
{
    QFile refs(QStringLiteral("/proc/self/clear_refs"));
    return refs.open(QIODevice::WriteOnly) && refs.write("5") == 1;
}

// The first word of each refusal.
QStringList reasons(const QSignalSpy& refused)
{
    QStringList out;
    for (const QList<QVariant>& r : refused)
        out << r.at(0).toString().section(QStringLiteral(": "), 0, 0);
    return out;
}

// A console publishing for the aircraft as GB_30226, signed, and what it says.
struct Primary {
    explicit Primary(const BrokerSettings& settings)
        : client(settings), publisher(&client, signedAs(kPrimary), &events), connected(&client, &MqttClient::connected)
    {
        publisher.setAircraft(kAircraft);
        publisher.setRole(QStringLiteral("control"), kPrimary, QStringLiteral("GB_41251"));
        client.start();
    }
    void frame(int i) { emit events.frameLogged(sentFrame(i)); }

    LinkEvents events;
    MqttClient client;
    SessionPublisher publisher;
    QSignalSpy connected;
};

}  // namespace

class TestBrokerTrust : public QObject {
    Q_OBJECT

private slots:
    void initTestCase()
    {
        QLocale::setDefault(QLocale(QLocale::English, QLocale::UnitedStates));
        QVERIFY(QFile::exists(QStringLiteral("/usr/sbin/mosquitto")));
    }

    // RFC 8032, section 7.1, tests 1 and 2: OpenSSL's Ed25519 as the
    // station key uses it.
    void ed25519KnownAnswers()
    {
        const auto key = [](const char* hex) {
            const std::optional<rcm::secure::StationPublicKey> bytes = rcm::secure::parseStationPublicKey(hex);
            return rcm::secure::SecretKey(*bytes);
        };
        const rcm::secure::StationSigningKey one(
            key("9d61b19deffd5a60ba844af492ec2cc44449c5697b326919703bac031cae7f60"));
        QCOMPARE(QString::fromStdString(rcm::secure::hexOf(one.publicKey())),
                 QStringLiteral("d75a980182b10ab7d54bfed3c964073a0ee172f3daa62325af021a68f707511a"));
        QCOMPARE(QString::fromStdString(rcm::secure::hexOf(one.sign({}))),
                 QStringLiteral("e5564300c360ac729086e2cc806e828a84877f1eb8e5d974d873e06522490155"
                                "5fb8821590a33bacc61e39701cf9b46bd25bf5f0595bbe24655141438e7a100b"));
        const rcm::secure::StationSigningKey two(
            key("4ccd089b28ff96da9db6c346ec114e0f5b8a319f35aba624da8cf6ed4fb8a6fb"));
        const std::uint8_t message[] = {0x72};
        const rcm::secure::StationSignature signature = two.sign(message);
        QCOMPARE(QString::fromStdString(rcm::secure::hexOf(signature)),
                 QStringLiteral("92a009a9f0d4cab8720e820b5f642540a2b27b5416503f8fb3762223ebdb69da"
                                "085ac1e43e15996e458f3613d0f11d8c387b2eaeb4302aeeb00d291612bb0c00"));
        QVERIFY(rcm::secure::verifyStationSignature(two.publicKey(), message, signature));
        const std::uint8_t other[] = {0x73};
        QVERIFY(!rcm::secure::verifyStationSignature(two.publicKey(), other, signature));
        QVERIFY(!rcm::secure::verifyStationSignature(one.publicKey(), message, signature));
    }

    // What a reader makes of one envelope: verified when the station's
    // trusted key signed exactly it, on exactly that topic; refused when
    // anything in it, or where it was published, was changed.
    void envelopeBoundToTopicStationAndNumber()
    {
        const QString topic = BrokerTopics::framesTopic(kAircraft, kPrimary);
        EnvelopeWriter writer = signedAs(kPrimary);
        const auto clock = std::make_shared<VirtualClock>(kT0);
        writer.setClock(clock);
        const QByteArray body = "{\"x\":1}";
        const QByteArray payload = writer.wrap(topic, body);
        QCOMPARE(writer.nextSeq(), kT0 + 1);  // the clock stood still: one more than the last
        clock->advance(std::chrono::milliseconds(500));
        QCOMPARE(writer.nextSeq(), kT0 + 500'000);

        const std::shared_ptr<BrokerTrust> trust = trusting({kPrimary});
        const OpenedMessage good = trust->open(topic, payload, false);
        QCOMPARE(good.trust, OpenedMessage::Trust::Verified);
        QCOMPARE(good.station, kPrimary);
        QCOMPARE(good.seq, kT0);
        QCOMPARE(good.body, body);
        QCOMPARE(good.where->kind, BrokerTopics::Kind::Frames);

        const auto refusal = [&](const QString& where, const QByteArray& p) {
            const OpenedMessage m = trust->open(where, p, false);
            return m.refused() ? m.refusal : QStringLiteral("taken");
        };
        const auto edited = [&](const char* from, const char* to) {
            QByteArray p = payload;
            return p.replace(from, to);
        };
        const QString forged = QStringLiteral("forged: GB_30226's signature does not verify on ") + topic;
        const QByteArray otherBody = edited("\\\"x\\\":1", "\\\"x\\\":2");
        QVERIFY(otherBody != payload);
        QCOMPARE(refusal(topic, otherBody), forged);
        QCOMPARE(refusal(topic, edited("1764000000000000", "1764000000000001")), forged);
        const QByteArray asWill = edited("\"v\":1", "\"will\":true,\"v\":1");
        QVERIFY(asWill != payload);
        QCOMPARE(refusal(topic, asWill), forged);
        // Moved to another topic of the same station, or another station's.
        const QString state = BrokerTopics::stateTopic(kAircraft, kPrimary);
        QCOMPARE(refusal(state, payload), QStringLiteral("forged: GB_30226's signature does not verify on ") + state);
        const QString other = BrokerTopics::framesTopic(kAircraft, QStringLiteral("GB_41251"));
        QCOMPARE(refusal(other, payload),
                 QStringLiteral("forged: a message naming GB_30226 on GB_41251's topic ") + other);
        // Unsigned, in the name of a station whose key is trusted.
        QCOMPARE(refusal(topic, EnvelopeWriter(kPrimary).wrap(topic, body)),
                 QStringLiteral("unsigned: a message in the name of GB_30226, whose key is trusted, on ") + topic);
        // Signed by someone else's key.
        EnvelopeWriter impostor(kPrimary, stationKey(QStringLiteral("AD_1")));
        QCOMPARE(refusal(topic, impostor.wrap(topic, body)), forged);
        // Not an envelope; too large; not our schema.
        QCOMPARE(refusal(topic, body),
                 QStringLiteral("malformed: %1: envelope: v is missing: not an envelope (a report published bare is "
                                "refused)")
                     .arg(topic));
        QCOMPARE(refusal(topic, QByteArray(16385, 'x')),
                 QStringLiteral("too large: 16385 bytes on %1, at most 16384").arg(topic));
        QCOMPARE(refusal(QStringLiteral("rcm/GB_133/frames"), payload),
                 QStringLiteral("malformed: rcm/GB_133/frames is not a topic of the rcm schema"));

        // A station nobody here trusts: unverified, signed or not; never refused for it.
        const QString theirs = BrokerTopics::framesTopic(kAircraft, QStringLiteral("AD_1"));
        QCOMPARE(trust->open(theirs, EnvelopeWriter(QStringLiteral("AD_1")).wrap(theirs, body), false).trust,
                 OpenedMessage::Trust::Unverified);
        QCOMPARE(trust->open(theirs, signedAs(QStringLiteral("AD_1")).wrap(theirs, body), false).trust,
                 OpenedMessage::Trust::Unverified);
        // Cleared: an empty retained message, nobody's to sign.
        QVERIFY(trust->open(topic, {}, true).cleared);

        // The envelope's JSON, field by field.
        QString error;
        const std::optional<BrokerEnvelope> e = BrokerEnvelope::fromJson(payload, &error);
        QVERIFY2(e, qPrintable(error));
        QCOMPARE(e->station, kPrimary);
        QCOMPARE(e->seq, kT0);
        QCOMPARE(e->signature.size(), 64);
        const QByteArray head = "{\"body\":\"{\\\"x\\\":1}\",\"seq\":1764000000000000,\"sig\":\"";
        QVERIFY2(payload.startsWith(head), payload.constData());
        QVERIFY2(payload.endsWith("\",\"station\":\"GB_30226\",\"v\":1}"), payload.constData());
        for (const auto& [json, what] : std::initializer_list<std::pair<const char*, const char*>>{
                 {R"({"v":2,"station":"S","seq":1,"body":""})", "envelope: v must be 1"},
                 {R"({"v":1,"station":"a/b","seq":1,"body":""})", "envelope: station must be a station's name"},
                 {R"({"v":1,"station":"S","seq":0,"body":""})", "envelope: seq must be a whole number from 1"},
                 {R"({"v":1,"station":"S","seq":1})", "envelope: must hold either body or sealed"},
                 {R"({"v":1,"station":"S","seq":1,"body":"","sig":"AAAA"})",
                  "envelope: sig must be 64 bytes in base64"},
                 {R"({"v":1,"station":"S","seq":1,"sealed":"AAAA","key":"12"})",
                  "envelope: key must be a key's fingerprint, 16 hex digits"},
             }) {
            QVERIFY(!BrokerEnvelope::fromJson(json, &error));
            QCOMPARE(error, QString::fromLatin1(what));
        }
    }

    // A station's messages on a topic in increasing number only: the same
    // number again is the broker's duplicate, an older one a replay; its
    // will, numbered before the reports that name it, is taken once.
    void sequenceAndWill()
    {
        SequenceCheck check;
        const auto message = [](qint64 seq, bool will = false, qint64 willSeq = 0) {
            OpenedMessage m;
            m.topic = BrokerTopics::stationTopic(kAircraft, kPrimary);
            m.station = kPrimary;
            m.seq = seq;
            m.will = will;
            m.willSeq = willSeq;
            return m;
        };
        using R = SequenceCheck::Result;
        QCOMPARE(check.check(message(10, false, 5)), R::Fresh);
        QCOMPARE(check.check(message(10, false, 5)), R::Duplicate);
        QCOMPARE(check.check(message(12, false, 5)), R::Fresh);
        QCOMPARE(check.check(message(11, false, 5)), R::Replayed);
        QCOMPARE(SequenceCheck::refusal(message(11), check.newest(message(11).topic)),
                 QStringLiteral("replayed: GB_30226's message 11 on rcm/GB_133/station/GB_30226 is not newer than "
                                "12, read before"));
        // The will the reports named: taken once, however late.
        QCOMPARE(check.check(message(5, true)), R::Fresh);
        QCOMPARE(check.check(message(5, true)), R::Duplicate);
        // Another old will: replayed.
        QCOMPARE(check.check(message(4, true)), R::Replayed);
        // A new session's reports name a new will.
        QCOMPARE(check.check(message(20, false, 19)), R::Fresh);
        QCOMPARE(check.check(message(5, true)), R::Replayed);
        QCOMPARE(check.check(message(19, true)), R::Fresh);
        // A stream (frames): a message sent again under its first number may
        // come after newer ones; taken once, unless older than all taken.
        SequenceCheck stream;
        const auto frame = [](qint64 seq) {
            OpenedMessage m;
            m.topic = BrokerTopics::framesTopic(kAircraft, kPrimary);
            m.where = BrokerTopics::parseTopic(m.topic);
            m.station = kPrimary;
            m.seq = seq;
            return m;
        };
        QCOMPARE(stream.check(frame(100)), R::Fresh);
        QCOMPARE(stream.check(frame(105)), R::Fresh);
        QCOMPARE(stream.check(frame(103)), R::Fresh);
        QCOMPARE(stream.check(frame(103)), R::Duplicate);
        QCOMPARE(stream.check(frame(99)), R::Replayed);
        for (qint64 i = 0; i < qint64(SequenceCheck::kStreamWindow); ++i)
            QCOMPARE(stream.check(frame(200 + i)), R::Fresh);
        QCOMPARE(stream.check(frame(105)), R::Replayed);  // out of the window now
        QCOMPARE(stream.check(frame(150)), R::Replayed);
        // A will newer than everything read: a late reader's first word.
        SequenceCheck late;
        QCOMPARE(late.check(message(30, true)), R::Fresh);
        QCOMPARE(late.check(message(31, false, 30)), R::Fresh);
    }

    // A keyed session's reports: opened only with the aircraft's key, only
    // on the topic they were sealed for.
    void sealOpensOnlyWithTheKey()
    {
        const rcm::secure::SecretKey psk = rcm::secure::generateKey();
        const rcm::LogKey linkKey(psk);
        const rcm::secure::SecretKey brokerKey = rcm::secure::deriveBrokerKey(psk);
        QCOMPARE(QString::fromStdString(rcm::secure::hexOf(linkKey.brokerKey().bytes())),
                 QString::fromStdString(rcm::secure::hexOf(brokerKey.bytes())));
        // Its own label: not the key of either direction of the link.
        const auto hex = [](const rcm::secure::SecretKey& k) { return rcm::secure::hexOf(k.bytes()); };
        QVERIFY(hex(rcm::secure::deriveDirectionKey(psk, rcm::secure::Direction::GcsToUa)) != hex(brokerKey));
        QVERIFY(hex(rcm::secure::deriveDirectionKey(psk, rcm::secure::Direction::UaToGcs)) != hex(brokerKey));
        QCOMPARE(rcm::secure::brokerKeyInfo(), std::string_view("RCM-GCS v1 broker AES-256-GCM"));

        const QString topic = BrokerTopics::stateTopic(kAircraft, kPrimary);
        EnvelopeWriter writer = signedAs(kPrimary);
        writer.setSealKey(linkKey.brokerKey(), QString::fromStdString(linkKey.fingerprint()));
        const QByteArray body = R"({"text":"ID_msg 12\nland_wheels Out"})";
        const QByteArray payload = writer.wrap(topic, body);
        QVERIFY(!payload.contains("land_wheels"));
        QVERIFY(!payload.contains("ID_msg"));
        QVERIFY(payload.contains(QByteArray("\"key\":\"") + linkKey.fingerprint().c_str() + '"'));

        std::shared_ptr<BrokerTrust> withKey = trusting({kPrimary});
        withKey->addLinkKey(linkKey);
        const OpenedMessage opened = withKey->open(topic, payload, false);
        QVERIFY(opened.verified());
        QVERIFY(opened.sealed);
        QVERIFY(opened.opened);
        QCOMPARE(opened.body, body);
        // Without the key: verified, and all it says is that it exists.
        const OpenedMessage closed = trusting({kPrimary})->open(topic, payload, false);
        QVERIFY(closed.verified());
        QVERIFY(!closed.opened);
        QCOMPARE(closed.body, QByteArray());
        QCOMPARE(closed.keyFingerprint, QString::fromStdString(linkKey.fingerprint()));
        // Another key bearing the same fingerprint cannot exist; a sealed
        // message moved, unsigned, from another topic does not open.
        EnvelopeWriter unsigned_(QStringLiteral("AD_1"));
        unsigned_.setSealKey(linkKey.brokerKey(), QString::fromStdString(linkKey.fingerprint()));
        const QString theirs = BrokerTopics::stateTopic(kAircraft, QStringLiteral("AD_1"));
        const QString elsewhere = BrokerTopics::eventsTopic(kAircraft, QStringLiteral("AD_1"));
        const OpenedMessage moved = withKey->open(elsewhere, unsigned_.wrap(theirs, body), false);
        QVERIFY(moved.refused());
        QCOMPARE(moved.refusal, QStringLiteral("forged: AD_1's sealed message on %1 does not open under the key %2")
                                    .arg(elsewhere, QString::fromStdString(linkKey.fingerprint())));

        // AES-256-GCM itself: a changed byte anywhere, another key, another topic.
        const QByteArray topicBytes = topic.toUtf8();
        const auto aad =
            std::span(reinterpret_cast<const std::uint8_t*>(topicBytes.constData()), std::size_t(topicBytes.size()));
        const auto plain = std::span(reinterpret_cast<const std::uint8_t*>(body.constData()), std::size_t(body.size()));
        std::vector<std::uint8_t> sealed = rcm::secure::sealBrokerPayload(brokerKey, aad, plain);
        QCOMPARE(sealed.size(), body.size() + rcm::secure::kSealOverhead);
        QVERIFY(rcm::secure::openBrokerPayload(brokerKey, aad, sealed).has_value());
        for (std::size_t i = 0; i < sealed.size(); ++i) {
            sealed[i] ^= 0x01;
            QVERIFY(!rcm::secure::openBrokerPayload(brokerKey, aad, sealed).has_value());
            sealed[i] ^= 0x01;
        }
        QVERIFY(!rcm::secure::openBrokerPayload(rcm::secure::generateKey(), aad, sealed).has_value());
        QVERIFY(!rcm::secure::openBrokerPayload(brokerKey, aad.first(aad.size() - 1), sealed).has_value());
        // Two seals of one body differ (a random nonce each).
        QVERIFY(rcm::secure::sealBrokerPayload(brokerKey, aad, plain) != sealed);
    }

    // A password file, a station key file, a trust file: refused when
    // others than their owner may read (or, for the trust file, change)
    // them, with the fix; gcs says so and stops.
    void filesOthersMayReadRefused()
    {
        QTemporaryDir dir;
        const QString passwords = dir.filePath(QStringLiteral("broker.password"));
        QFile f(passwords);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("s3cret pass\nsecond line\n");
        f.close();
        QFile::setPermissions(passwords, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadGroup | QFile::ReadOther);
        QString error;
        QVERIFY(!BrokerSettings::readPasswordFile(passwords, &error));
        QCOMPARE(error, QStringLiteral("the password file %1 has mode 0644: others than its owner may read or write "
                                       "it, so it is refused; run: chmod 600 %1")
                            .arg(passwords));
        const rcm::test::ProgramRun refused = rcm::test::runProgram(
            QStringLiteral("gcs"),
            {QStringLiteral("--broker"), QStringLiteral("mqtt://127.0.0.1:1/"), QStringLiteral("--broker-user"),
             QStringLiteral("ops"), QStringLiteral("--broker-password-file"), passwords});
        QCOMPARE(refused.exitCode, 2);
        QVERIFY2(refused.err.contains(QStringLiteral("gcs: --broker-password-file: %1\n").arg(error).toUtf8()),
                 refused.err.constData());
        QFile::setPermissions(passwords, QFile::ReadOwner | QFile::WriteOwner);
        QCOMPARE(BrokerSettings::readPasswordFile(passwords, &error),
                 std::optional<QString>(QStringLiteral("s3cret pass")));

        // The station's signing key: as a link key file.
        const QString keyPath = dir.filePath(QStringLiteral("GB_30226.key"));
        std::string keyError;
        QVERIFY(stationKey(kPrimary)->writeFile(keyPath.toStdString(), keyError));
        const auto key = rcm::secure::StationSigningKey::fromFile(keyPath.toStdString(), keyError);
        QVERIFY(key);
        QCOMPARE(key->publicKey(), stationKey(kPrimary)->publicKey());
        QFile::setPermissions(keyPath, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadGroup);
        QVERIFY(!rcm::secure::StationSigningKey::fromFile(keyPath.toStdString(), keyError));
        QCOMPARE(QString::fromStdString(keyError),
                 QStringLiteral("the key file %1 has mode 0640: others than its owner may read or write it, so it is "
                                "refused; run: chmod 600 %1")
                     .arg(keyPath));

        // The trust file: public, but nobody else may change it.
        const QString trustPath = dir.filePath(QStringLiteral("trusted-stations"));
        QFile t(trustPath);
        QVERIFY(t.open(QIODevice::WriteOnly));
        t.write("# the fleet's stations\n\nGB_30226 " +
                QByteArray::fromStdString(rcm::secure::hexOf(stationKey(kPrimary)->publicKey())) + "\n");
        t.close();
        QFile::setPermissions(
            trustPath, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadGroup | QFile::WriteGroup | QFile::ReadOther);
        QVERIFY(!BrokerTrust::fromFile(trustPath, &error));
        QCOMPARE(error, QStringLiteral("the trust file %1 has mode 0664: others than its owner may change whom this "
                                       "console trusts, so it is refused; run: chmod 644 %1")
                            .arg(trustPath));
        QFile::setPermissions(trustPath, QFile::ReadOwner | QFile::WriteOwner | QFile::ReadGroup | QFile::ReadOther);
        const std::optional<BrokerTrust> trust = BrokerTrust::fromFile(trustPath, &error);
        QVERIFY2(trust, qPrintable(error));
        QCOMPARE(trust->trustedStations(), QStringList{kPrimary});
        QVERIFY(t.open(QIODevice::Append));
        t.write("GB_41251 0123\n");
        t.close();
        QVERIFY(!BrokerTrust::fromFile(trustPath, &error));
        QCOMPARE(error,
                 QStringLiteral("the trust file %1 line 4: the public key must be 64 hex digits").arg(trustPath));

        // rcm stationkey: the key file, and the trust line to hand out.
        const QString made = dir.filePath(QStringLiteral("GB_41251.key"));
        const rcm::test::ProgramRun run = rcm::test::runProgram(
            QStringLiteral("rcm"), {QStringLiteral("stationkey"), QStringLiteral("GB_41251"), made});
        QCOMPARE(run.exitCode, 0);
        QVERIFY(QFile::permissions(made) ==
                (QFile::ReadOwner | QFile::WriteOwner | QFile::ReadUser | QFile::WriteUser));
        const auto madeKey = rcm::secure::StationSigningKey::fromFile(made.toStdString(), keyError);
        QVERIFY(madeKey);
        QCOMPARE(run.out, "GB_41251 " + QByteArray::fromStdString(rcm::secure::hexOf(madeKey->publicKey())) + "\n");
        // Again: the same line, the key untouched.
        const rcm::test::ProgramRun again = rcm::test::runProgram(
            QStringLiteral("rcm"), {QStringLiteral("stationkey"), QStringLiteral("GB_41251"), made});
        QCOMPARE(again.exitCode, 0);
        QCOMPARE(again.out, run.out);
        QCOMPARE(again.err, QStringLiteral("rcm: %1 exists already: its trust line, unchanged\n").arg(made).toUtf8());
    }

    // The issue's attacks, by an anonymous mosquitto_pub on the broker the
    // primary and its observer use: a retained station report naming
    // another station in control, the same as an unsigned envelope, a new
    // station claiming control, a frame from the future, a frame signed
    // with another key, an alarm event, a plain command frame, a genuine
    // message replayed. The observer refuses each (counted, said), follows
    // the primary throughout, and shows none of it.
    void forgeriesRefusedByTheObserver()
    {
        MosquittoProcess broker;
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        Primary primary(local(broker.port()));
        QTRY_COMPARE_WITH_TIMEOUT(primary.connected.count(), 1, kTimeoutMs);
        // What went on the broker, to replay one of the primary's messages.
        MqttClient wiretap(local(broker.port()));
        QSignalSpy carried(&wiretap, &MqttClient::messageReceived);
        wiretap.subscribe(BrokerTopics::aircraftPattern(kAircraft), 1);
        QSignalSpy tapped(&wiretap, &MqttClient::connected);
        wiretap.start();
        QTRY_COMPARE_WITH_TIMEOUT(tapped.count(), 1, kTimeoutMs);

        BrokerObservation observer(observing(broker.port(), trusting({kPrimary})));
        QSignalSpy refused(&observer, &BrokerObservation::messageRefused);
        QSignalSpy warnings(&observer, &BrokerObservation::warning);
        QSignalSpy logged(&observer, &LinkEvents::frameLogged);
        QSignalSpy errors(&observer, &LinkEvents::errorOccurred);
        QSignalSpy events(&observer, &BrokerObservation::eventReported);
        observer.start();
        QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kPrimary), kTimeoutMs);
        QCOMPARE(observer.followedStation(), kPrimary);
        primary.frame(1);
        primary.frame(2);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);
        // A second station report, so that the first is an old one.
        primary.publisher.setDescription(QStringLiteral("UDP 127.0.0.1:5600"));
        QTRY_COMPARE_WITH_TIMEOUT(observer.stations().value(kPrimary).description, QStringLiteral("UDP 127.0.0.1:5600"),
                                  kTimeoutMs);
        QTRY_VERIFY_WITH_TIMEOUT(carried.count() >= 4, kTimeoutMs);

        const quint16 port = broker.port();
        const QString stationTopic = BrokerTopics::stationTopic(kAircraft, kPrimary);
        const QString framesTopic = BrokerTopics::framesTopic(kAircraft, kPrimary);
        const QString eventsTopic = BrokerTopics::eventsTopic(kAircraft, kPrimary);
        StationReport claim;
        claim.station = kPrimary;
        claim.role = QStringLiteral("control");
        claim.link = LinkState::Connected;
        claim.online = true;
        claim.utcMicros = kT0 + 3'600'000'000;
        claim.destination = QStringLiteral("AD_1");
        // a: the report bare, as the issue published it.
        QCOMPARE(mosquittoPub(port, stationTopic, claim.toJson(), true), 0);
        // b: in an envelope, unsigned.
        QCOMPARE(mosquittoPub(port, stationTopic, EnvelopeWriter(kPrimary).wrap(stationTopic, claim.toJson()), true),
                 0);
        // c: a station of its own, claiming control: unverified, not refused.
        StationReport ad1 = claim;
        ad1.station = QStringLiteral("AD_1");
        const QString ad1Topic = BrokerTopics::stationTopic(kAircraft, QStringLiteral("AD_1"));
        QCOMPARE(
            mosquittoPub(port, ad1Topic, EnvelopeWriter(QStringLiteral("AD_1")).wrap(ad1Topic, ad1.toJson()), true), 0);
        // d: a frame from the future, unsigned; e: signed with another key.
        FrameReport future;
        future.station = kPrimary;
        future.direction = FrameDirection::Sent;
        future.utcMicros = kT0 + 86'400'000'000;
        future.bytes = frameBytes(99);
        future.session = 1;
        future.seq = 1'000'000;
        QCOMPARE(mosquittoPub(port, framesTopic, EnvelopeWriter(kPrimary).wrap(framesTopic, future.toJson()), false),
                 0);
        EnvelopeWriter impostor(kPrimary, stationKey(QStringLiteral("AD_1")));
        QCOMPARE(mosquittoPub(port, framesTopic, impostor.wrap(framesTopic, future.toJson()), false), 0);
        // f: an alarm event.
        const EventReport alarm{kT0, QStringLiteral("alarm"), QStringLiteral("ENGINE FIRE"), kPrimary};
        QCOMPARE(mosquittoPub(port, eventsTopic, EnvelopeWriter(kPrimary).wrap(eventsTopic, alarm.toJson()), false), 0);
        // g: a command frame, bare.
        QCOMPARE(mosquittoPub(port, framesTopic, future.toJson(), false), 0);
        // h: the primary's first station report again, genuine and signed,
        // after a later one: replayed. Its first frame again: a duplicate of
        // what the observer read, dropped without a word.
        const auto firstOn = [&](const QString& topic) {
            for (const QList<QVariant>& m : std::as_const(carried))
                if (m.at(0).toString() == topic)
                    return m.at(1).toByteArray();
            return QByteArray();
        };
        QVERIFY(!firstOn(stationTopic).isEmpty() && !firstOn(framesTopic).isEmpty());
        QCOMPARE(mosquittoPub(port, stationTopic, firstOn(stationTopic), false), 0);
        QCOMPARE(mosquittoPub(port, framesTopic, firstOn(framesTopic), false), 0);

        QTRY_COMPARE_WITH_TIMEOUT(refused.count(), 7, kTimeoutMs);
        QCOMPARE(reasons(refused),
                 (QStringList{"malformed", "unsigned", "unsigned", "forged", "unsigned", "malformed", "replayed"}));
        QVERIFY2(refused.at(6).at(0).toString().startsWith(
                     QStringLiteral("replayed: GB_30226's message %1 on %2 is not newer than ")
                         .arg(BrokerEnvelope::fromJson(firstOn(stationTopic), nullptr)->seq)
                         .arg(stationTopic)),
                 qPrintable(refused.at(6).at(0).toString()));
        QCOMPARE(refused.at(3).at(0).toString(),
                 QStringLiteral("forged: GB_30226's signature does not verify on ") + framesTopic);
        QCOMPARE(observer.refusedMessages(), quint64(7));
        // The primary goes on; the observer still follows it, as it was.
        primary.frame(3);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 3, kTimeoutMs);
        QCOMPARE(logged.at(2).at(0).value<LoggedFrame>().bytes, frameBytes(3));
        QCOMPARE(observer.followedStation(), kPrimary);
        QCOMPARE(observer.stations().value(kPrimary).destination, kPrimary);
        QCOMPARE(observer.stations().keys(), QStringList{kPrimary});
        QCOMPARE(observer.unverifiedStations(), QStringList{QStringLiteral("AD_1")});
        QCOMPARE(warnings.count(), 1);
        QCOMPARE(warnings.at(0).at(0).toString(),
                 QStringLiteral("broker: AD_1 publishes for GB_133 unverified (its key is not trusted here): not "
                                "shown; trust its key (--broker-trust) to observe it"));
        QCOMPARE(errors.count(), 0);
        QCOMPARE(events.count(), 0);
        QCOMPARE(observer.missedFrames(), quint64(0));

        // A late observer finds the forged retained reports on the broker:
        // refused too, and it follows the primary by its frames.
        BrokerObservation late(observing(broker.port(), trusting({kPrimary})));
        QSignalSpy lateRefused(&late, &BrokerObservation::messageRefused);
        QSignalSpy lateLogged(&late, &LinkEvents::frameLogged);
        late.start();
        QTRY_COMPARE_WITH_TIMEOUT(lateRefused.count(), 1, kTimeoutMs);
        QCOMPARE(reasons(lateRefused), QStringList{"unsigned"});
        QTRY_VERIFY_WITH_TIMEOUT(late.isConnected(), kTimeoutMs);
        primary.frame(4);
        QTRY_COMPARE_WITH_TIMEOUT(lateLogged.count(), 1, kTimeoutMs);
        QCOMPARE(late.followedStation(), kPrimary);
        QCOMPARE(late.unverifiedStations(), QStringList{QStringLiteral("AD_1")});
    }

    // One 50 MB message, retained, on a broker with no limit of its own, and
    // one of 40 KB: the first never reaches the observer (the broker does
    // not send it a packet over its maximum), the second is dropped before
    // it is read and counted; the observer's memory does not grow with
    // either, and it goes on.
    void hugeMessagesDroppedMemoryBounded()
    {
        MosquittoProcess broker;
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        Primary primary(local(broker.port()));
        BrokerObservation observer(observing(broker.port(), trusting({kPrimary})));
        QSignalSpy refused(&observer, &BrokerObservation::messageRefused);
        QSignalSpy logged(&observer, &LinkEvents::frameLogged);
        observer.start();
        QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kPrimary), kTimeoutMs);
        primary.frame(1);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 1, kTimeoutMs);

        QVERIFY(resetPeak());
        const qint64 before = statusKiB("VmRSS");
        const QString framesTopic = BrokerTopics::framesTopic(kAircraft, kPrimary);
        QCOMPARE(mosquittoPubHuge(broker.port(), framesTopic, 50, true), 0);
        const QString eventsTopic = BrokerTopics::eventsTopic(kAircraft, kPrimary);
        QCOMPARE(mosquittoPub(broker.port(), eventsTopic, QByteArray(40 * 1024, 'y'), false), 0);
        QTRY_COMPARE_WITH_TIMEOUT(refused.count(), 1, kTimeoutMs);
        QCOMPARE(refused.at(0).at(0).toString(),
                 QStringLiteral("too large: 40960 bytes on %1, at most 8192").arg(eventsTopic));
        primary.frame(2);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);
        QCOMPARE(logged.at(1).at(0).value<LoggedFrame>().bytes, frameBytes(2));
        const qint64 peak = statusKiB("VmHWM");
        QVERIFY2(peak - before < 16 * 1024,
                 qPrintable(QStringLiteral("grew from %1 KiB to a peak of %2 KiB").arg(before).arg(peak)));
        QCOMPARE(refused.count(), 1);

        // A console joining later is not sent the retained 50 MB either.
        BrokerObservation late(observing(broker.port(), trusting({kPrimary})));
        QSignalSpy lateLogged(&late, &LinkEvents::frameLogged);
        late.start();
        QTRY_VERIFY_WITH_TIMEOUT(late.stations().contains(kPrimary), kTimeoutMs);
        primary.frame(3);
        QTRY_COMPARE_WITH_TIMEOUT(lateLogged.count(), 1, kTimeoutMs);
        QVERIFY(statusKiB("VmHWM") - before < 16 * 1024);
    }

    // The deployment configuration (resources/mosquitto/rcm.conf): a
    // password for everyone, each station writing only its own topics,
    // nothing over 16 KiB, sessions kept over a restart. An observer whose
    // broker restarts misses nothing: what the primary published meanwhile
    // comes, every frame once, and both say the broker's return.
    void deploymentBrokerRestartFillsTheGap()
    {
        MosquittoProcess broker({{},
                                 {},
                                 false,
                                 true,
                                 {{kPrimary, QStringLiteral("primary pass")},
                                  {QStringLiteral("observer-ops"), QStringLiteral("observer pass")}}});
        QVERIFY2(broker.start(), qPrintable(broker.setupError()));
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        BrokerSettings primarySettings = local(broker.port());
        primarySettings.user = kPrimary;
        primarySettings.password = QStringLiteral("primary pass");
        Primary primary(primarySettings);
        QSignalSpy primaryBack(&primary.client, &MqttClient::restored);
        BrokerSettings observerSettings = observing(broker.port(), trusting({kPrimary}));
        observerSettings.user = QStringLiteral("observer-ops");
        observerSettings.password = QStringLiteral("observer pass");
        BrokerObservation observer(observerSettings);
        QSignalSpy logged(&observer, &LinkEvents::frameLogged);
        QSignalSpy status(&observer, &LinkEvents::transportStatusChanged);
        QSignalSpy warnings(&observer, &BrokerObservation::warning);
        QSignalSpy refused(&observer, &BrokerObservation::messageRefused);
        observer.start();
        QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kPrimary), kTimeoutMs);
        primary.frame(1);
        primary.frame(2);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);

        // Nobody else writes in the primary's name: the broker refuses the
        // observer's user, and anyone without a password.
        MqttClient intruder(observerSettings);
        intruder.setTrust({});
        QSignalSpy intruderUp(&intruder, &MqttClient::connected);
        QSignalSpy intruderRefused(&intruder, &MqttClient::refusedByBroker);
        intruder.start();
        QTRY_COMPARE_WITH_TIMEOUT(intruderUp.count(), 1, kTimeoutMs);
        const QString framesTopic = BrokerTopics::framesTopic(kAircraft, kPrimary);
        QVERIFY(intruder.publish(framesTopic, EnvelopeWriter(kPrimary).wrap(framesTopic, "{}"), 1, false));
        QTRY_COMPARE_WITH_TIMEOUT(intruderRefused.count(), 1, kTimeoutMs);
        QCOMPARE(intruderRefused.at(0).at(0).toString(),
                 QStringLiteral("broker 127.0.0.1:%1 refused a message on %2: not authorized")
                     .arg(broker.port())
                     .arg(framesTopic));
        QVERIFY(mosquittoPub(broker.port(), framesTopic, "{}", false) != 0);
        // Nor anything larger than any console publishes, from anyone.
        QVERIFY(mosquittoPubHuge(broker.port(), BrokerTopics::framesTopic(kAircraft, QStringLiteral("observer-ops")),
                                 50, true,
                                 {QStringLiteral("-u"), QStringLiteral("observer-ops"), QStringLiteral("-P"),
                                  QStringLiteral("observer pass")}) != 0);
        intruder.stop();

        // The broker restarts; the primary logs frames while it is away.
        QVERIFY(broker.stop());
        for (int i = 3; i <= 6; ++i)
            primary.frame(i);
        QVERIFY(broker.start());
        QTRY_COMPARE_WITH_TIMEOUT(primaryBack.count(), 1, kRejoinTimeoutMs);
        QTRY_VERIFY_WITH_TIMEOUT(observer.isConnected(), kRejoinTimeoutMs);
        primary.frame(7);  // the session kept: no need to wait for the subscription
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 7, kTimeoutMs);
        for (int i = 0; i < 7; ++i)
            QCOMPARE(logged.at(i).at(0).value<LoggedFrame>().bytes, frameBytes(i + 1));
        QCOMPARE(observer.missedFrames(), quint64(0));
        QCOMPARE(warnings.count(), 0);
        QCOMPARE(refused.count(), 0);
        QVERIFY2(primaryBack.at(0).at(0).toString().startsWith(
                     QStringLiteral("broker 127.0.0.1:%1: back after ").arg(broker.port())),
                 qPrintable(primaryBack.at(0).at(0).toString()));
        bool said = false;
        for (const QList<QVariant>& s : std::as_const(status))
            said = said ||
                   s.at(0).toString().startsWith(QStringLiteral("broker 127.0.0.1:%1: back after ").arg(broker.port()));
        QVERIFY(said);
        // Nothing of the 50 MB was kept: a client that takes packets of any
        // size hears nothing on its topic.
        BrokerSettings anySize = observerSettings;
        anySize.maxPacketBytes = 0;
        MqttClient listener(anySize);
        listener.setTrust({});
        QSignalSpy heard(&listener, &MqttClient::messageReceived);
        listener.subscribe(BrokerTopics::framesTopic(kAircraft, QStringLiteral("observer-ops")), 1);
        QSignalSpy listening(&listener, &MqttClient::subscribed);
        listener.start();
        QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);
        QVERIFY(!heard.wait(1000));
    }

    // A broker without persistence, restarted, and an observer that comes
    // back only after the primary has published what it kept meanwhile:
    // those frames are gone for it, and it says how many.
    void brokerRestartGapCounted()
    {
        MosquittoProcess broker;
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        // Each through a relay, so that who comes back when is the test's to say.
        TcpRelay primaryRelay(broker.port());
        TcpRelay observerRelay(broker.port());
        Primary primary(local(primaryRelay.port()));
        BrokerObservation observer(observing(observerRelay.port(), trusting({kPrimary})));
        QSignalSpy logged(&observer, &LinkEvents::frameLogged);
        QSignalSpy warnings(&observer, &BrokerObservation::warning);
        observer.start();
        QTRY_VERIFY_WITH_TIMEOUT(observer.stations().contains(kPrimary), kTimeoutMs);
        primary.frame(1);
        primary.frame(2);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);

        QVERIFY(broker.stop());
        primaryRelay.cut();
        observerRelay.cut();
        for (int i = 3; i <= 6; ++i)
            primary.frame(i);
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        MqttClient listener(local(broker.port()));
        QSignalSpy heard(&listener, &MqttClient::messageReceived);
        QSignalSpy listening(&listener, &MqttClient::subscribed);
        listener.subscribe(BrokerTopics::framesTopic(kAircraft, kPrimary), 1);
        listener.start();
        QTRY_COMPARE_WITH_TIMEOUT(listening.count(), 1, kTimeoutMs);
        // The primary is back and publishes frames 3 to 6, which only the
        // listener, subscribed anew, hears: the observer is still away.
        // (Some perhaps twice: at least once is QoS 1's promise.)
        QVERIFY(primaryRelay.reopen());
        const auto heardFrames = [&] {
            std::set<quint64> numbers;
            for (const QList<QVariant>& m : std::as_const(heard))
                if (const auto e = BrokerEnvelope::fromJson(m.at(1).toByteArray(), nullptr))
                    if (const auto f = FrameReport::fromJson(e->body, nullptr))
                        numbers.insert(f->seq);
            return numbers;
        };
        QTRY_COMPARE_WITH_TIMEOUT(heardFrames(), (std::set<quint64>{3, 4, 5, 6}), kRejoinTimeoutMs);
        QSignalSpy resubscribed(observer.client(), &MqttClient::subscribed);
        QVERIFY(observerRelay.reopen());
        QTRY_COMPARE_WITH_TIMEOUT(resubscribed.count(), 1, kRejoinTimeoutMs);
        primary.frame(7);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 3, kTimeoutMs);
        QCOMPARE(logged.at(2).at(0).value<LoggedFrame>().bytes, frameBytes(7));
        QCOMPARE(observer.missedFrames(), quint64(4));
        QCOMPARE(warnings.count(), 1);
        QCOMPARE(warnings.at(0).at(0).toString(),
                 QStringLiteral("broker: missed 4 frames of GB_30226 (its frames 3 to 6 never came)"));
    }

    // TLS: the right CA and password connect; without a CA file the
    // system's CA certificates are trusted (so the tests' CA is not); a
    // missing CA file, a wrong password and an untrusted server are said as
    // failures of the set-up, which the console puts in its banner, never
    // "publishing".
    void tlsMisconfigurationSurfaced()
    {
        MosquittoProcess broker({{}, {}, false, true, {{kPrimary, QStringLiteral("primary pass")}}});
        QVERIFY2(broker.start(), qPrintable(broker.setupError()));
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        QString urlError;
        std::optional<BrokerSettings> tls = BrokerSettings::fromUrl(
            QStringLiteral("mqtts://%1@127.0.0.1:%2").arg(kPrimary).arg(broker.tlsPort()), &urlError);
        QVERIFY2(tls, qPrintable(urlError));
        tls->password = QStringLiteral("primary pass");

        BrokerSettings right = *tls;
        right.caFile = broker.caFile();
        MqttClient good(right);
        QSignalSpy goodUp(&good, &MqttClient::connected);
        QSignalSpy goodFailed(&good, &MqttClient::setupFailed);
        good.start();
        QTRY_COMPARE_WITH_TIMEOUT(goodUp.count(), 1, kTimeoutMs);
        QCOMPARE(goodFailed.count(), 0);

        const auto failure = [](const BrokerSettings& settings) {
            MqttClient client(settings);
            QSignalSpy failed(&client, &MqttClient::setupFailed);
            QSignalSpy errors(&client, &MqttClient::errorOccurred);
            client.start();
            if (!failed.wait(kTimeoutMs) && failed.isEmpty())
                return QStringLiteral("no failure said");
            return errors.isEmpty() ? failed.at(0).at(0).toString() : QStringLiteral("also an error");
        };
        const QString where = QStringLiteral("broker 127.0.0.1:%1: ").arg(broker.tlsPort());
        const QString systemCa = failure(*tls);
        QVERIFY2(systemCa.startsWith(where + QStringLiteral("TLS failed")) &&
                     systemCa.contains(QStringLiteral("certificate verify failed")),
                 qPrintable(systemCa));
        BrokerSettings missing = *tls;
        missing.caFile = broker.dir() + QStringLiteral("/none.crt");
        QCOMPARE(failure(missing), where + QStringLiteral("TLS: cannot read \"%1\": no such file").arg(missing.caFile));
        BrokerSettings wrongPassword = right;
        wrongPassword.password = QStringLiteral("guess");
        QCOMPARE(failure(wrongPassword), where + QStringLiteral("connection refused: not authorized"));

        // The console: the failure in its event log as an error and on the
        // banner; no word of publishing.
        QTemporaryDir home;
        qputenv("XDG_CONFIG_HOME", home.filePath(QStringLiteral("config")).toUtf8());
        qputenv("XDG_DATA_HOME", home.filePath(QStringLiteral("data")).toUtf8());
        MainWindow::Options options;
        options.restoreSettings = false;
        MainWindow window(options);
        QSignalSpy recorded(window.alerts()->events(), &EventLog::recorded);
        window.joinBroker(missing, true);
        const QString said = where + QStringLiteral("TLS: cannot read \"%1\": no such file").arg(missing.caFile);
        QTRY_COMPARE_WITH_TIMEOUT(window.alerts()->errorBanner()->currentText(), said, kTimeoutMs);
        bool logged = false;
        for (const QList<QVariant>& r : std::as_const(recorded)) {
            const auto e = r.at(0).value<ConsoleEvent>();
            logged = logged || (e.severity == EventSeverity::Error && e.text == said);
            QVERIFY2(!e.text.contains(QStringLiteral("connected, publishing")), qPrintable(e.text));
        }
        QVERIFY(logged);
    }

    // A keyed session seen by an observer that holds the aircraft's key: the
    // frames the station sent, enciphered as they went on the air, are read
    // with the key, and the panels show what the station commands; without
    // the key, only that the session exists.
    void observerWindowReadsKeyedSession()
    {
        MosquittoProcess broker;
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        const rcm::secure::SecretKey psk = rcm::secure::generateKey();
        const auto linkKey = std::make_shared<const rcm::LogKey>(psk);
        LinkEvents events;
        MqttClient client(local(broker.port()));
        EnvelopeWriter envelopes = signedAs(kPrimary);
        envelopes.setSealKey(linkKey->brokerKey(), QString::fromStdString(linkKey->fingerprint()));
        SessionPublisher publisher(&client, std::move(envelopes), &events);
        publisher.setAircraft(kAircraft);
        publisher.setRole(QStringLiteral("control"), kPrimary, {});
        QSignalSpy publishing(&client, &MqttClient::connected);
        client.start();
        QTRY_COMPARE_WITH_TIMEOUT(publishing.count(), 1, kTimeoutMs);

        // The gear up, enciphered for the aircraft as the link sends it.
        rcm::Message command = rcm::restingCommand(rcm::Airframe::wellEquipped());
        command.header.set(rcm::ItemId::ID_msg, 4242);
        command.header.set(rcm::ItemId::time_UTC, 120000);
        command.header.set(rcm::ItemId::date_UTC, 251124);
        command.settings.set(rcm::ItemId::land_wheels, rcm::withEveryFieldCode(rcm::code::kRetracted));
        const rcm::secure::SecureCodec up(psk, rcm::secure::Direction::GcsToUa);
        rcm::Diagnostics errors;
        const std::optional<rcm::EncodedBlocks> blocks = up.encode(command, errors);
        QVERIFY2(blocks, errors.empty() ? "" : errors.front().toString().c_str());
        const rcm::DatagramBytes datagram = rcm::makeDatagram(blocks->block1, blocks->block2);
        LoggedFrame sent = sentFrame(1);
        sent.entry.enciphered = true;
        sent.bytes = QByteArray(reinterpret_cast<const char*>(datagram.data()), qsizetype(datagram.size()));

        QTemporaryDir home;
        qputenv("XDG_CONFIG_HOME", home.filePath(QStringLiteral("config")).toUtf8());
        qputenv("XDG_DATA_HOME", home.filePath(QStringLiteral("data")).toUtf8());
        MainWindow::Options options;
        options.restoreSettings = false;
        MainWindow window(options);
        std::shared_ptr<BrokerTrust> trust = trusting({kPrimary});
        trust->addLinkKey(linkKey);
        const BrokerSettings settings = observing(broker.port(), trust);
        window.joinBroker(settings, false);
        window.observe(settings);
        QSignalSpy logged(window.observation(), &LinkEvents::frameLogged);
        QTRY_VERIFY_WITH_TIMEOUT(window.observation()->stations().contains(kPrimary), kTimeoutMs);
        const unsigned before = window.command()->message().settings.fieldCode(rcm::ItemId::land_wheels, 0);
        QVERIFY(before != rcm::code::kRetracted);
        emit events.frameLogged(sent);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 1, kTimeoutMs);
        QCOMPARE(logged.at(0).at(0).value<LoggedFrame>().bytes, sent.bytes);
        QCOMPARE(window.command()->message().settings.fieldCode(rcm::ItemId::land_wheels, 0), rcm::code::kRetracted);
        QCOMPARE(window.command()->message().header.number(rcm::ItemId::ID_msg), 4242);

        // Without the key: sealed, and said once.
        BrokerObservation blind(observing(broker.port(), trusting({kPrimary})));
        QSignalSpy blindLogged(&blind, &LinkEvents::frameLogged);
        QSignalSpy blindWarnings(&blind, &BrokerObservation::warning);
        blind.start();
        QTRY_VERIFY_WITH_TIMEOUT(blind.sealedStations().contains(kPrimary), kTimeoutMs);
        QCOMPARE(blind.sealedStations().value(kPrimary), QString::fromStdString(linkKey->fingerprint()));
        QVERIFY(blind.stations().isEmpty());
        sent.entry.utcMicros += 1'000'000;
        emit events.frameLogged(sent);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);
        QCOMPARE(blindLogged.count(), 0);
        QCOMPARE(blindWarnings.count(), 1);
        QCOMPARE(blindWarnings.at(0).at(0).toString(),
                 QStringLiteral("broker: GB_30226's session with GB_133 is keyed and sealed (key fingerprint %1): "
                                "give that key (--key) to observe it")
                     .arg(QString::fromStdString(linkKey->fingerprint())));
    }

    // A password sent over plain mqtt:// is warned about; the observer
    // window never sends anything to the aircraft, whatever the broker
    // carries: no link runs, no datagram leaves.
    void observerWindowSendsNothing()
    {
        MosquittoProcess broker;
        QVERIFY(broker.start());
        QTRY_VERIFY_WITH_TIMEOUT(broker.accepts(), kTimeoutMs);
        Primary primary(local(broker.port()));
        QUdpSocket aircraft;
        QVERIFY(aircraft.bind(QHostAddress::LocalHost, 0));

        QTemporaryDir home;
        qputenv("XDG_CONFIG_HOME", home.filePath(QStringLiteral("config")).toUtf8());
        qputenv("XDG_DATA_HOME", home.filePath(QStringLiteral("data")).toUtf8());
        MainWindow::Options options;
        options.restoreSettings = false;
        MainWindow window(options);
        LinkSettings link;
        link.transport = LinkSettings::Transport::Udp;
        link.remoteAddress = QStringLiteral("127.0.0.1");
        link.remotePort = aircraft.localPort();
        window.linkSettings()->setSettings(link);
        BrokerSettings settings = observing(broker.port(), trusting({kPrimary}));
        settings.user = QStringLiteral("ops");
        settings.password = QStringLiteral("pass");
        QSignalSpy recorded(window.alerts()->events(), &EventLog::recorded);
        window.joinBroker(settings, false);
        window.observe(settings);
        bool warned = false;
        const QString warning = QStringLiteral(
                                    "The broker password goes to 127.0.0.1:%1 over plain mqtt://, "
                                    "unencrypted: anyone on the path reads it; use mqtts://")
                                    .arg(broker.port());
        for (const QList<QVariant>& r : std::as_const(recorded)) {
            const auto e = r.at(0).value<ConsoleEvent>();
            warned = warned || (e.severity == EventSeverity::Warning && e.text == warning);
        }
        QVERIFY(warned);
        QSignalSpy logged(window.observation(), &LinkEvents::frameLogged);
        QTRY_VERIFY_WITH_TIMEOUT(window.observation()->stations().contains(kPrimary), kTimeoutMs);
        primary.frame(1);
        const QString framesTopic = BrokerTopics::framesTopic(kAircraft, kPrimary);
        FrameReport injected;
        injected.station = kPrimary;
        injected.direction = FrameDirection::Sent;
        injected.utcMicros = kT0;
        injected.bytes = frameBytes(5);
        QCOMPARE(mosquittoPub(broker.port(), framesTopic, injected.toJson(), false), 0);
        primary.frame(2);
        QTRY_COMPARE_WITH_TIMEOUT(logged.count(), 2, kTimeoutMs);
        QVERIFY(!window.session()->isRunning());
        QVERIFY(!aircraft.waitForReadyRead(1000));
        QCOMPARE(aircraft.pendingDatagramSize(), qint64(-1));
    }
};

QTEST_MAIN(TestBrokerTrust)
#include "tst_broker_trust.moc"
