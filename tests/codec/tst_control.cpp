// The aircraft's side of control between stations (codec/control/
// ControlArbiter.h, docs/protocol.md section 10): every row of the rules
// table, failover with and without the backup heard, a handover undone by
// failover, taking up, the backup changed by the station in control, frames
// naming stations the aircraft does not have, the texts said, and the
// single-station aircraft. Time is what each call passes: no clock.
#include "codec/control/ControlArbiter.h"

#include <QtTest>

#include <chrono>

using namespace rcm;
using namespace std::chrono_literals;
using Kind = ControlArbiter::Event::Kind;

namespace {

constexpr StationId kA{44, 30226};  // GB_30226, first: in control at start
constexpr StationId kB{44, 41251};  // GB_41251, second: the backup at start
constexpr StationId kX{44, 52000};  // GB_52000, a third station of the aircraft's
constexpr StationId kZ{33, 7};      // FR_7: no channel of this aircraft's

// 2027-01-15 08:00:00 UTC.
constexpr std::int64_t kT0 = 1'800'000'000'000'000;

constexpr std::int64_t at(std::chrono::microseconds offset)
{
    return kT0 + offset.count();
}

// What a decision said, for one comparison.
QStringList texts(const ControlArbiter::Decision& d)
{
    QStringList out;
    for (const ControlArbiter::Event& e : d.events)
        out << QString::fromStdString(e.text);
    return out;
}

// The station in control, then the backup, then whether taken up: "GB_30226 GB_41251 taken".
QString state(const ControlArbiter& a)
{
    const auto name = [](std::optional<StationId> s) {
        return s ? QStringLiteral("%1_%2").arg(s->country).arg(s->unit) : QStringLiteral("-");
    };
    return name(a.controller()) + QLatin1Char(' ') + name(a.backup()) +
           (a.takenUp() ? QStringLiteral(" taken") : QStringLiteral(" offered"));
}

// A with control taken up at kT0, B the backup.
ControlArbiter takenUpByA(std::chrono::microseconds failover = ControlArbiter::kDefaultFailover)
{
    ControlArbiter a({kA, kB}, failover);
    a.onFrame(kA, kA, kA, kT0);  // the claim: A's operator took control
    return a;
}

}  // namespace

class TestControl : public QObject {
    Q_OBJECT

private slots:
    void startsWithTheFirstInControlNotYetTakenUp()
    {
        const ControlArbiter a({kA, kB});
        QVERIFY(!a.singleStation());
        QCOMPARE(a.failover(), std::chrono::microseconds(5s));
        QCOMPARE(*a.controller(), kA);
        QCOMPARE(*a.backup(), kB);
        QVERIFY(!a.takenUp());
        QCOMPARE(a.notInControlCount(kA), quint64(0));
        QCOMPARE(a.notInControlCount(kB), quint64(0));
    }

    // Row 1: S = C and D = S, taken up by the claim (D = B = S) alone.
    void controllerClaimingTakesUpAndIsActedOn()
    {
        ControlArbiter a({kA, kB});
        // Naming itself is not enough: what a console just restarted sends.
        const ControlArbiter::Decision named = a.onFrame(kA, kA, kB, kT0);
        QVERIFY(!named.act);
        QCOMPARE(named.notActedOn,
                 std::string("control not yet taken up (GB_30226 in control, waiting for its operator's Take control)"));
        QVERIFY(named.events.empty());
        QVERIFY(!a.onFrame(kA, kA, std::nullopt, kT0).act);
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 offered"));

        QVERIFY(ControlArbiter::isClaim(kA, kA, kA));
        QVERIFY(!ControlArbiter::isClaim(kA, kA, kB));
        QVERIFY(!ControlArbiter::isClaim(kA, kB, kB));
        QVERIFY(!ControlArbiter::isClaim(kA, std::nullopt, std::nullopt));
        const ControlArbiter::Decision first = a.onFrame(kA, kA, kA, kT0);
        QVERIFY(first.act);
        QVERIFY(first.notActedOn.empty());
        QCOMPARE(first.events.size(), std::size_t{1});
        QCOMPARE(first.events[0].kind, Kind::TakenUp);
        QCOMPARE(texts(first), QStringList{"taken up: GB_30226 in control, GB_41251 backup"});
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));

        // Taken up, its frames naming itself are commands, claims or not.
        const ControlArbiter::Decision next = a.onFrame(kA, kA, kB, at(1s));
        QVERIFY(next.act);
        QVERIFY(next.events.empty());
        QVERIFY(a.onFrame(kA, kA, kA, at(2s)).act);
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
    }

    // After a failover a backup console restarted (or one that lost control)
    // names itself as before; the aircraft does not take it up for that.
    void stationGivenControlNamingItselfIsNotTakenUp()
    {
        ControlArbiter a = takenUpByA();
        a.onFrame(kB, kA, kB, at(1s));
        QVERIFY(a.tick(at(5s)));
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        for (int s = 6; s <= 8; ++s) {
            const ControlArbiter::Decision d = a.onFrame(kB, kB, std::nullopt, at(std::chrono::seconds(s)));
            QVERIFY(!d.act);
            QVERIFY(d.events.empty());
            QVERIFY(!a.onFrame(kB, kB, kA, at(std::chrono::seconds(s))).act);
        }
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        // A claim from a station not in control is counted, not taken up.
        QVERIFY(!a.onFrame(kA, kA, kA, at(9s)).act);
        QCOMPARE(a.notInControlCount(kA), quint64(1));
        QVERIFY(a.onFrame(kB, kB, kB, at(9s)).act);
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 taken"));
    }

    // Row 1, the backup it names: another of the aircraft's stations becomes K.
    void controllerChangesItsBackup()
    {
        ControlArbiter a({kA, kB, kX});
        QCOMPARE(texts(a.onFrame(kA, kA, kA, kT0)), QStringList{"taken up: GB_30226 in control, GB_41251 backup"});
        const ControlArbiter::Decision d = a.onFrame(kA, kA, kX, kT0);
        QVERIFY(d.act);
        QCOMPARE(texts(d), QStringList{"backup changed: GB_52000, named by GB_30226 in control (was GB_41251)"});
        QCOMPARE(d.events[0].kind, Kind::BackupChanged);
        QCOMPARE(state(a), QStringLiteral("44_30226 44_52000 taken"));

        // B is now only an observer; X the one that takes over. Watching, as
        // a backup does (naming A), is not counted against B.
        QVERIFY(!a.onFrame(kB, kA, kX, at(1s)).act);
        QCOMPARE(a.notInControlCount(kB), quint64(0));
        a.onFrame(kX, kA, kX, at(1s));
        QVERIFY(!a.tick(at(4'999'999us)));  // A was heard at kT0: not yet silent for 5 s
        const auto failover = a.tick(at(5s));
        QVERIFY(failover);
        QCOMPARE(failover->text, std::string("failover: nothing from GB_30226 for 5 s; GB_52000 in control, not yet "
                                             "taken up"));
        QCOMPARE(state(a), QStringLiteral("44_52000 44_30226 offered"));
    }

    // Row 1, a backup that is not "another of the aircraft's stations": K stays.
    void backupNamedThatIsNotAnotherStationIsKept_data()
    {
        QTest::addColumn<std::optional<StationId>>("named");
        QTest::newRow("not the aircraft's") << std::optional<StationId>(kZ);
        QTest::newRow("itself") << std::optional<StationId>(kA);
        QTest::newRow("the backup it has") << std::optional<StationId>(kB);
        QTest::newRow("none") << std::optional<StationId>();
    }
    void backupNamedThatIsNotAnotherStationIsKept()
    {
        QFETCH(std::optional<StationId>, named);
        ControlArbiter a = takenUpByA();
        const ControlArbiter::Decision d = a.onFrame(kA, kA, named, at(1s));
        QVERIFY(d.act);
        QVERIFY(d.events.empty());
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
    }

    // Row 2: S = C, taken up, D = K.
    void handoverGivesControlToTheBackupNotYetTakenUp()
    {
        ControlArbiter a = takenUpByA();
        const ControlArbiter::Decision d = a.onFrame(kA, kB, kA, at(1s));
        QVERIFY(!d.act);  // the frame's commands are not acted on
        QCOMPARE(d.notActedOn, std::string("a handover"));
        QCOMPARE(d.events.size(), std::size_t{1});
        QCOMPARE(d.events[0].kind, Kind::Handover);
        QCOMPARE(texts(d), QStringList{"handover: GB_30226 hands control to GB_41251, not yet taken up"});
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));

        // Nobody's commands until B takes up: not A's, though it named itself.
        QVERIFY(!a.onFrame(kA, kA, kB, at(2s)).act);
        QCOMPARE(a.notInControlCount(kA), quint64(1));
        // B, given control, names the backup as destination: not yet taken
        // up; nor by naming itself, only by its claim.
        QVERIFY(!a.onFrame(kB, kA, kB, at(2s)).act);
        QVERIFY(!a.onFrame(kB, kB, kA, at(3s)).act);
        const ControlArbiter::Decision taken = a.onFrame(kB, kB, kB, at(3s));
        QVERIFY(taken.act);
        QCOMPARE(texts(taken), QStringList{"taken up: GB_41251 in control, GB_30226 backup"});
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 taken"));
    }

    // Row 3: S = C, not yet taken up, D not S.
    void controllerNotYetTakenUpNamingAnotherIsNothing_data()
    {
        QTest::addColumn<std::optional<StationId>>("destination");
        QTest::addColumn<QString>("why");
        QTest::newRow("the backup") << std::optional<StationId>(kB)
                                    << "control not yet taken up (names GB_41251 as destination)";
        QTest::newRow("not the aircraft's")
            << std::optional<StationId>(kZ) << "control not yet taken up (names FR_7 as destination)";
        QTest::newRow("none") << std::optional<StationId>()
                              << "control not yet taken up (names no station as destination)";
    }
    void controllerNotYetTakenUpNamingAnotherIsNothing()
    {
        QFETCH(std::optional<StationId>, destination);
        ControlArbiter a({kA, kB});
        const ControlArbiter::Decision d = a.onFrame(kA, destination, kA, kT0);
        QVERIFY(!d.act);
        QFETCH(QString, why);
        QCOMPARE(QString::fromStdString(d.notActedOn), why);
        QVERIFY(d.events.empty());
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 offered"));
        QCOMPARE(a.notInControlCount(kA), quint64(0));
    }

    // Row 4: S not C.
    void stationNotInControlIsCountedAndHeard()
    {
        ControlArbiter a = takenUpByA();
        const ControlArbiter::Decision first = a.onFrame(kB, kB, kA, at(1s));
        QVERIFY(!first.act);
        QCOMPARE(first.notActedOn, std::string("not in control"));
        QCOMPARE(first.events.size(), std::size_t{1});
        QCOMPARE(first.events[0].kind, Kind::NotInControl);
        QCOMPARE(texts(first), QStringList{"not in control: GB_41251's frames are not acted on; GB_30226 in control"});
        // Counted every time, said once until control changes.
        for (int s = 2; s <= 4; ++s) {
            const ControlArbiter::Decision d = a.onFrame(kB, kB, kA, at(std::chrono::seconds(s)));
            QVERIFY(!d.act);
            QVERIFY(d.events.empty());
        }
        QCOMPARE(a.notInControlCount(kB), quint64(4));
        QCOMPARE(a.notInControlCount(kA), quint64(0));
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
        // Heard: A silent 5 s with B heard within them is a failover.
        QVERIFY(a.tick(at(5s)));
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        // Control changed: A, not in control now, is told once.
        QCOMPARE(texts(a.onFrame(kA, kA, kB, at(6s))),
                 QStringList{"not in control: GB_30226's frames are not acted on; GB_41251 in control"});
        QCOMPARE(a.notInControlCount(kA), quint64(1));
    }

    // "A frame that names a station other than its sender in ID_GCS_destination is not a command."
    void controllerNamingAStationThatIsNotTheBackupIsNothing_data()
    {
        QTest::addColumn<std::optional<StationId>>("destination");
        QTest::addColumn<QString>("why");
        QTest::newRow("not the aircraft's") << std::optional<StationId>(kZ) << "names FR_7 as destination, not itself";
        QTest::newRow("another of its stations")
            << std::optional<StationId>(kX) << "names GB_52000 as destination, not itself";
        QTest::newRow("none") << std::optional<StationId>() << "names no station as destination, not itself";
    }
    void controllerNamingAStationThatIsNotTheBackupIsNothing()
    {
        QFETCH(std::optional<StationId>, destination);
        ControlArbiter a({kA, kB, kX});
        a.onFrame(kA, kA, kA, kT0);
        const ControlArbiter::Decision d = a.onFrame(kA, destination, kB, at(1s));
        QVERIFY(!d.act);
        QFETCH(QString, why);
        QCOMPARE(QString::fromStdString(d.notActedOn), why);
        QVERIFY(d.events.empty());
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
    }

    void senderWithoutAChannelIsNobody()
    {
        ControlArbiter a = takenUpByA();
        const ControlArbiter::Decision d = a.onFrame(kZ, kZ, kA, at(1s));
        QVERIFY(!d.act);
        QCOMPARE(d.notActedOn, std::string("no channel of this aircraft's"));
        QVERIFY(d.events.empty());
        QCOMPARE(a.notInControlCount(kZ), quint64(0));
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
    }

    void failoverWithTheBackupHeard()
    {
        ControlArbiter a = takenUpByA();
        a.onFrame(kB, kA, kB, at(4s));
        QVERIFY(!a.tick(at(4'999'999us)));
        const std::optional<ControlArbiter::Event> e = a.tick(at(5s));
        QVERIFY(e);
        QCOMPARE(e->kind, Kind::Failover);
        QCOMPARE(e->text,
                 std::string("failover: nothing from GB_30226 for 5 s; GB_41251 in control, not yet taken up"));
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        QVERIFY(!a.tick(at(6s)));  // once

        // Taking up: B's frames naming A (it has not yet seen the change) are
        // nothing; its claim is acted on.
        QVERIFY(!a.onFrame(kB, kA, kB, at(6s)).act);
        const ControlArbiter::Decision taken = a.onFrame(kB, kB, kB, at(7s));
        QVERIFY(taken.act);
        QCOMPARE(texts(taken), QStringList{"taken up: GB_41251 in control, GB_30226 backup"});
    }

    void noFailoverWithoutTheBackupHeard()
    {
        ControlArbiter a = takenUpByA();
        QVERIFY(!a.tick(at(5s)));
        QVERIFY(!a.tick(at(60s)));
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));

        // Heard, but not within the failover time: still nothing.
        a.onFrame(kA, kA, kB, at(61s));
        a.onFrame(kB, kA, kB, at(62s));
        QVERIFY(!a.tick(at(67s)));  // A silent 6 s, B 5 s
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 taken"));
        a.onFrame(kB, kA, kB, at(68s));
        QVERIFY(a.tick(at(68s)));
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
    }

    // At start the station in control has the failover time to be heard,
    // counted from the first time the arbiter is told.
    void firstStationNeverHeardFailsOverFromStart()
    {
        ControlArbiter a({kA, kB}, 2s);
        QVERIFY(!a.tick(kT0));
        a.onFrame(kB, kB, kA, at(1s));
        QVERIFY(!a.tick(at(1'999'999us)));
        const auto e = a.tick(at(2s));
        QVERIFY(e);
        QCOMPARE(e->text,
                 std::string("failover: nothing from GB_30226 for 2 s; GB_41251 in control, not yet taken up"));
    }

    // A handover to a backup that never takes up control is undone by
    // failover, the failover time after the handover, back to the station
    // that handed over, which takes it up again the same way.
    void handoverThenFailoverBack()
    {
        ControlArbiter a = takenUpByA();
        a.onFrame(kB, kA, kB, at(1s));  // B's last frame
        QVERIFY(!a.onFrame(kA, kB, kA, at(2s)).act);
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        // A, now the backup, goes on as one: naming B in control.
        for (int s = 3; s <= 7; ++s)
            QVERIFY(!a.onFrame(kA, kB, kA, at(std::chrono::seconds(s))).act);
        // B was last heard at 1 s, but has had control only since 2 s.
        QVERIFY(!a.tick(at(6'999'999us)));
        const auto e = a.tick(at(7s));
        QVERIFY(e);
        QCOMPARE(e->text,
                 std::string("failover: nothing from GB_41251 for 5 s; GB_30226 in control, not yet taken up"));
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 offered"));
        QVERIFY(!a.onFrame(kA, kB, kA, at(8s)).act);
        const ControlArbiter::Decision taken = a.onFrame(kA, kA, kA, at(9s));
        QVERIFY(taken.act);
        QCOMPARE(texts(taken), QStringList{"taken up: GB_30226 in control, GB_41251 backup"});
        // A named B while it was the backup: watching, not counted.
        QCOMPARE(a.notInControlCount(kA), quint64(0));
    }

    // A handover to a backup that is there but does not take control up (its
    // operator does not answer): the offer lapses after the failover time,
    // back to the station that handed over, and is offered again.
    void offerNotTakenUpLapses()
    {
        ControlArbiter a = takenUpByA();
        QVERIFY(!a.onFrame(kA, kB, kA, at(1s)).act);  // hands over
        QCOMPARE(state(a), QStringLiteral("44_41251 44_30226 offered"));
        for (int s = 2; s <= 6; ++s) {
            // B, given control but not taking it up, names A as its console does;
            // A, the backup now, names B.
            QVERIFY(!a.onFrame(kB, kA, kB, at(std::chrono::seconds(s))).act);
            QVERIFY(!a.onFrame(kA, kB, kA, at(std::chrono::seconds(s))).act);
        }
        QVERIFY(!a.tick(at(5'999'999us)));
        const auto e = a.tick(at(6s));
        QVERIFY(e);
        QCOMPARE(e->kind, Kind::Lapsed);
        QCOMPARE(e->text,
                 std::string("not taken up: GB_41251 did not take control within 5 s; GB_30226 in control, not yet "
                             "taken up"));
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 offered"));
        // Taken up by A: nothing lapses any more.
        QVERIFY(a.onFrame(kA, kA, kA, at(7s)).act);
        a.onFrame(kB, kA, kB, at(12s));
        QVERIFY(a.onFrame(kA, kA, kB, at(12s)).act);
        QVERIFY(!a.tick(at(13s)));
    }

    // Control configured at start is not an offer: it does not lapse while
    // its station is heard, however late it takes it up.
    void controlAtStartDoesNotLapse()
    {
        ControlArbiter a({kA, kB});
        for (int s = 0; s <= 10; ++s) {
            a.onFrame(kA, kB, kA, at(std::chrono::seconds(s)));
            a.onFrame(kB, kA, kB, at(std::chrono::seconds(s)));
            QVERIFY(!a.tick(at(std::chrono::seconds(s))));
        }
        QCOMPARE(state(a), QStringLiteral("44_30226 44_41251 offered"));
    }

    void failoverTimeIsSaidAsGiven()
    {
        ControlArbiter a = takenUpByA(2500ms);
        a.onFrame(kB, kA, kB, at(2s));
        const auto e = a.tick(at(2500ms));
        QVERIFY(e);
        QCOMPARE(e->text,
                 std::string("failover: nothing from GB_30226 for 2.5 s; GB_41251 in control, not yet taken up"));
    }

    // One station, or none configured: as before there were several.
    void singleStationActsOnEverything_data()
    {
        QTest::addColumn<std::vector<StationId>>("stations");
        QTest::newRow("unconfigured") << std::vector<StationId>{};
        QTest::newRow("one station") << std::vector<StationId>{kA};
        QTest::newRow("one station named twice") << std::vector<StationId>{kA, kA};
    }
    void singleStationActsOnEverything()
    {
        QFETCH(std::vector<StationId>, stations);
        ControlArbiter a(stations);
        QVERIFY(a.singleStation());
        QVERIFY(a.takenUp());
        QVERIFY(!a.controller() && !a.backup());
        const ControlArbiter::Decision d = a.onFrame(kA, kZ, kX, kT0);
        QVERIFY(d.act);
        QVERIFY(d.events.empty());
        // It follows what the frames name.
        QCOMPARE(*a.controller(), kZ);
        QCOMPARE(*a.backup(), kX);
        QVERIFY(a.onFrame(kB, std::nullopt, kB, at(1s)).act);
        QCOMPARE(*a.controller(), kZ);
        QCOMPARE(*a.backup(), kB);
        // A claim names its station twice: the backup stays.
        QVERIFY(a.onFrame(kA, kA, kA, at(2s)).act);
        QCOMPARE(*a.controller(), kA);
        QCOMPARE(*a.backup(), kB);
        QVERIFY(!a.tick(at(1h)));
        QCOMPARE(a.notInControlCount(kB), quint64(0));
    }
};

QTEST_GUILESS_MAIN(TestControl)
#include "tst_control.moc"
