// The console's side of control between stations (docs/protocol.md section
// 10): the role StationControl reads from the status frames, what it makes
// the console's frames name, and what it tells the operator.
#include "codec/message/ItemTable.h"
#include "codec/message/TextFormat.h"
#include "link/session/StationControl.h"

#include <QSignalSpy>
#include <QTest>

using namespace rcm;
using Role = StationControl::Role;

namespace {

const StationId kPrimary{44, 30226};  // GB_30226
const StationId kBackup{44, 41251};   // GB_41251
const StationId kOther{33, 7};        // FR_7

Message status(std::optional<StationId> control, std::optional<StationId> backup)
{
    Message m;
    if (control)
        m.header.set(ItemId::ID_GCS_destination, Value::station(*control));
    if (backup)
        m.header.set(ItemId::ID_GCS_backup, Value::station(*backup));
    return m;
}

// What a command becomes when control names it: {destination, backup}.
std::pair<QString, QString> named(const StationControl& control, const Message& command = {})
{
    Message m = command;
    control.applyTo(m);
    const auto text = [&](ItemId id) {
        const Value* v = m.header.find(id);
        return v ? QString::fromStdString(
                       formatStation({static_cast<std::uint16_t>(v->number), static_cast<std::uint16_t>(v->second)}))
                 : QStringLiteral("-");
    };
    return {text(ItemId::ID_GCS_destination), text(ItemId::ID_GCS_backup)};
}

using Named = std::pair<QString, QString>;

}  // namespace

class TestStationControl : public QObject {
    Q_OBJECT

private slots:
    void stationText()
    {
        QCOMPARE(formatStation(kPrimary), std::string("GB_30226"));
        QCOMPARE(parseStation("GB_30226"), std::optional<StationId>(kPrimary));
        QCOMPARE(parseStation("44_30226"), std::optional<StationId>(kPrimary));
        std::string error;
        QVERIFY(!parseStation("GB30226", &error));
        QCOMPARE(QString::fromStdString(error),
                 QStringLiteral("expected a station COUNTRY_UNIT such as GB_133 or 44_133 (ISO alpha-2 country or "
                                "dialling code, then the unit number), got 'GB30226'"));
        QVERIFY(!parseStation("ZZ_1", &error));
        QVERIFY(QString::fromStdString(error).startsWith(QStringLiteral("unknown country 'ZZ'")));
        QVERIFY(!parseStation("GB_1 GB_2", &error));
        QCOMPARE(QString::fromStdString(error),
                 QStringLiteral("expected a station COUNTRY_UNIT such as GB_133, got 'GB_1 GB_2'"));
    }

    void withoutAStationNothingIsFollowed()
    {
        StationControl control;
        QSignalSpy roles(&control, &StationControl::roleChanged);
        Message command = status(kOther, kBackup);
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Unknown);
        QCOMPARE(named(control, command), Named("FR_7", "GB_41251"));
        QCOMPARE(roles.count(), 0);
        QCOMPARE(control.describe(), QString());
        // Never a claim: only Take control, which follows control, sends one.
        QCOMPARE(named(control, status(kOther, kOther)), Named("FR_7", "-"));
    }

    // Until the aircraft says who is in control, the frames name nobody:
    // not a command, and no backup changed.
    void beforeAnyStatusTheStationNamesNobody()
    {
        StationControl control;
        control.setStation(kPrimary);
        QCOMPARE(named(control), Named("-", "-"));
        QCOMPARE(named(control, status(kOther, kBackup)), Named("-", "-"));
        QVERIFY(!control.canHandOver());
        QVERIFY(!control.canTakeControl());
    }

    // Named in control by the aircraft (its start-up configuration here):
    // the station names itself, claims nothing, until its operator takes
    // control; then every frame is the claim.
    void inControlOnlyOnceTaken()
    {
        StationControl control;
        control.setStation(kPrimary);
        QSignalSpy events(&control, &StationControl::event);
        QSignalSpy alarms(&control, &StationControl::alarm);
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(named(control, status(kOther, kOther)), Named("GB_30226", "-"));
        QCOMPARE(events.count(), 1);
        QCOMPARE(events.at(0).at(0).toString(),
                 QStringLiteral("The aircraft names this station in control: check what it reports, then Take "
                                "control to command it"));
        QCOMPARE(alarms.count(), 0);
        QVERIFY(control.canTakeControl());
        QVERIFY(!control.canHandOver());

        control.takeControl();
        QCOMPARE(control.role(), Role::InControl);
        QCOMPARE(events.at(1).at(0).toString(),
                 QStringLiteral("Taking control: the next frames claim control for this station"));
        QCOMPARE(named(control, status(kOther, kOther)), Named("GB_30226", "GB_30226"));
        QCOMPARE(control.describe(), QStringLiteral("GB_30226: in control, backup GB_41251"));
        QVERIFY(control.canHandOver());
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::InControl);
        QCOMPARE(alarms.count(), 0);
    }

    void startingAsBackupNamesTheStationInControl()
    {
        StationControl control;
        control.setStation(kBackup);
        QSignalSpy events(&control, &StationControl::event);
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Backup);
        QCOMPARE(named(control), Named("GB_30226", "GB_41251"));
        QCOMPARE(events.at(0).at(0).toString(), QStringLiteral("This station is the backup; GB_30226 in control"));
        QCOMPARE(control.describe(), QStringLiteral("GB_41251: backup, GB_30226 in control"));
        QVERIFY(!control.canHandOver());
        QVERIFY(!control.canTakeControl());
    }

    void failoverAwayIsAnAlarm()
    {
        StationControl control;
        control.setStation(kPrimary);
        control.statusReceived(status(kPrimary, kBackup));
        control.takeControl();
        QSignalSpy alarms(&control, &StationControl::alarm);
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Backup);
        QCOMPARE(alarms.count(), 1);
        QCOMPARE(alarms.at(0).at(0).toString(),
                 QStringLiteral("Control lost: the aircraft names GB_41251 in control, and this station did not "
                                "hand over"));
        QCOMPARE(named(control), Named("GB_41251", "GB_30226"));
        // The same status again says nothing more.
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(alarms.count(), 1);
        // Given control back, it claims nothing until taken again.
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(named(control), Named("GB_30226", "-"));
    }

    void givenControlWaitsForTheOperator()
    {
        StationControl control;
        control.setStation(kBackup);
        control.statusReceived(status(kPrimary, kBackup));
        QSignalSpy alarms(&control, &StationControl::alarm);
        QSignalSpy header(&control, &StationControl::headerChanged);
        // Failover: the aircraft names this station in control.
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(alarms.count(), 1);
        QCOMPARE(alarms.at(0).at(0).toString(),
                 QStringLiteral("The aircraft gave control to this station (GB_30226 was in control): check what it "
                                "reports, then Take control to command it"));
        QCOMPARE(header.count(), 1);
        // Naming itself without claiming: the aircraft acts on none of it yet.
        QCOMPARE(named(control), Named("GB_41251", "-"));
        QVERIFY(control.canTakeControl());
        QVERIFY(!control.canHandOver());

        control.takeControl();
        QCOMPARE(control.role(), Role::InControl);
        QCOMPARE(header.count(), 2);
        QCOMPARE(named(control), Named("GB_41251", "GB_41251"));
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::InControl);
        QCOMPARE(alarms.count(), 1);
    }

    void handOverWaitsForTheAircraft()
    {
        StationControl control;
        control.setStation(kPrimary);
        control.statusReceived(status(kPrimary, kBackup));
        control.takeControl();
        QSignalSpy alarms(&control, &StationControl::alarm);
        QSignalSpy events(&control, &StationControl::event);
        control.handOver();
        QCOMPARE(control.role(), Role::HandingOver);
        QCOMPARE(named(control), Named("GB_41251", "GB_30226"));
        QCOMPARE(events.at(0).at(0).toString(), QStringLiteral("Handing over to GB_41251"));
        // The aircraft has not seen it yet: still handing over, no alarm.
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::HandingOver);
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Backup);
        QCOMPARE(events.at(1).at(0).toString(),
                 QStringLiteral("Handed over: GB_41251 is in control, this station is its backup"));
        QCOMPARE(alarms.count(), 0);
        QCOMPARE(named(control), Named("GB_41251", "GB_30226"));
        // The backup never took control up: the offer lapses back here.
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(alarms.count(), 1);
        QCOMPARE(named(control), Named("GB_30226", "-"));
        // Not taken here either: it goes on to the backup again.
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Backup);
        QCOMPARE(alarms.count(), 2);
        QCOMPARE(alarms.at(1).at(0).toString(),
                 QStringLiteral("Control went to GB_41251: this station did not take it within the aircraft's "
                                "failover time"));
    }

    void handOverNeedsABackup()
    {
        StationControl control;
        control.setStation(kPrimary);
        control.statusReceived(status(kPrimary, std::nullopt));
        control.takeControl();
        QVERIFY(!control.canHandOver());
        control.handOver();
        QCOMPARE(control.role(), Role::InControl);
        QCOMPARE(named(control), Named("GB_30226", "GB_30226"));
    }

    void observingAThirdStation()
    {
        StationControl control;
        control.setStation(kOther);
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Observing);
        QCOMPARE(named(control), Named("GB_30226", "GB_41251"));
        QCOMPARE(control.describe(), QStringLiteral("FR_7: observing, GB_30226 in control"));
    }

    void aNewLinkDoesNotTakeControlUp()
    {
        StationControl control;
        control.setStation(kBackup);
        control.statusReceived(status(kPrimary, kBackup));
        control.statusReceived(status(kBackup, kPrimary));  // given control, not taken
        control.reset();                                    // the link drops and comes back
        QCOMPARE(control.role(), Role::Unknown);
        QCOMPARE(named(control), Named("-", "-"));
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(named(control), Named("GB_41251", "-"));
    }

    void aNewLinkFindingAnotherInControlIsAnAlarm()
    {
        StationControl control;
        control.setStation(kPrimary);
        control.statusReceived(status(kPrimary, kBackup));
        control.takeControl();
        control.reset();  // the link drops; the aircraft fails over meanwhile
        QSignalSpy alarms(&control, &StationControl::alarm);
        control.statusReceived(status(kBackup, kPrimary));
        QCOMPARE(control.role(), Role::Backup);
        QCOMPARE(alarms.count(), 1);
        QCOMPARE(named(control), Named("GB_41251", "GB_30226"));
    }

    // Control taken on one link is taken again on the next: a console
    // reconnected (or restarted) never claims by itself.
    void aNewLinkNeedsTakeControlAgain()
    {
        StationControl control;
        control.setStation(kPrimary);
        control.statusReceived(status(kPrimary, kBackup));
        control.takeControl();
        control.reset();
        QCOMPARE(named(control), Named("-", "-"));
        QSignalSpy events(&control, &StationControl::event);
        QSignalSpy alarms(&control, &StationControl::alarm);
        control.statusReceived(status(kPrimary, kBackup));
        QCOMPARE(control.role(), Role::Offered);
        QCOMPARE(named(control), Named("GB_30226", "-"));
        QCOMPARE(events.at(0).at(0).toString(),
                 QStringLiteral("The aircraft still names this station in control: check what it reports, then Take "
                                "control to command it again"));
        QCOMPARE(alarms.count(), 0);
    }
};

QTEST_GUILESS_MAIN(TestStationControl)
#include "tst_stationcontrol.moc"
