// Airframe files: what the console and the simulated aircraft both read.
#include "link/AirframeFile.h"

#include <QtTest>

using rcm::Airframe;

class TestAirframe : public QObject {
    Q_OBJECT
private slots:
    void roundTripsTheDefault();
    void readsAMinimalFile();
    void shippedAirframesLoad();
    void errorsSayWhatAndWhere_data();
    void errorsSayWhatAndWhere();
};

void TestAirframe::roundTripsTheDefault()
{
    const Airframe a = Airframe::wellEquipped();
    QString error;
    const auto back = parseAirframe(airframeToJson(a), "mem", &error);
    QVERIFY2(back, qPrintable(error));
    QCOMPARE(back->name, a.name);
    QCOMPARE(back->engines.size(), std::size_t{3});
    QCOMPARE(back->radios[2].systemId, std::string("VHF3"));
    QCOMPARE(back->cameras[1].maker, std::string("NIK"));
    QCOMPARE(back->cameras[1].number, 2);
    QCOMPARE(back->senseAndAvoid, true);
}

void TestAirframe::readsAMinimalFile()
{
    QString error;
    const auto a = parseAirframe(R"({"name": "Glider", "senseAndAvoid": false, "engines": []})", "g.json", &error);
    QVERIFY2(a, qPrintable(error));
    QCOMPARE(a->name, std::string("Glider"));
    QVERIFY(a->engines.empty() && a->radios.empty() && a->cameras.empty());
    QCOMPARE(a->senseAndAvoid, false);
}

void TestAirframe::shippedAirframesLoad()
{
    const QDir dir(QStringLiteral(RCM_SOURCE_DIR "/resources/airframes"));
    const QStringList files = dir.entryList({"*.json"});
    for (const QString& f : files) {
        QString error;
        QVERIFY2(loadAirframe(dir.filePath(f), &error), qPrintable(error));
    }
}

void TestAirframe::errorsSayWhatAndWhere_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");
    QTest::newRow("not json") << QByteArray("{\"name\": ") << "a.json: invalid JSON at byte offset 9: ";
    QTest::newRow("array") << QByteArray("[]") << "a.json: the top level must be a JSON object";
    QTest::newRow("engine id") << QByteArray(R"({"engines": [{"id": 1}, {"id": 300}]})")
                               << "a.json: engines[1].id must be 0..255";
    QTest::newRow("engine twice") << QByteArray(R"({"engines": [{"id": 2}, {"id": 2}]})")
                                  << "a.json: engines[1].id 2 is given twice";
    QTest::newRow("radio id") << QByteArray(R"({"radios": [{"systemId": "TOOLONGID"}]})")
                              << "a.json: radios[0].systemId \"TOOLONGID\" must be 1..8 printable ASCII characters";
    QTest::newRow("camera maker") << QByteArray(R"({"cameras": [{"maker": "NIKON", "number": 1}]})")
                                  << "a.json: cameras[0].maker \"NIKON\" must be 3 printable ASCII characters";
    QTest::newRow("camera number") << QByteArray(R"({"cameras": [{"maker": "NIK"}]})")
                                   << "a.json: cameras[0].number must be 0..255";
}

void TestAirframe::errorsSayWhatAndWhere()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    QString got;
    QVERIFY(!parseAirframe(json, "a.json", &got));
    QVERIFY2(got.startsWith(error), qPrintable(got));
}

QTEST_APPLESS_MAIN(TestAirframe)
#include "tst_airframe.moc"
