// Airframe files: the one reader the console and the simulated aircraft share.
#include "link/airframe/AirframeLoader.h"

#include <QtTest>

using rcm::Airframe;

class TestAirframe : public QObject {
    Q_OBJECT
private slots:
    void roundTripsTheDefault();
    void readsAMinimalFile();
    void builtInAirframesLoad();
    void shippedFilesMatchTheBuiltIns();
    void errorsSayWhatAndWhere_data();
    void errorsSayWhatAndWhere();
};

void TestAirframe::roundTripsTheDefault()
{
    const Airframe a = Airframe::wellEquipped();
    QString error;
    const auto back = AirframeLoader::fromJson(AirframeLoader::toJson(a), "mem", &error);
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
    const auto a = AirframeLoader::fromJson(R"({"name": "Glider", "senseAndAvoid": false})", "g.json", &error);
    QVERIFY2(a, qPrintable(error));
    QCOMPARE(a->name, std::string("Glider"));
    QVERIFY(a->engines.empty() && a->radios.empty() && a->cameras.empty());
    QCOMPARE(a->senseAndAvoid, false);
}

void TestAirframe::builtInAirframesLoad()
{
    const QStringList paths = AirframeLoader::builtIn();
    QVERIFY(paths.contains(AirframeLoader::kDefaultPath));
    for (const QString& path : paths) {
        QString error;
        QVERIFY2(AirframeLoader::load(path, &error), qPrintable(error));
    }
    const auto def = AirframeLoader::load(AirframeLoader::kDefaultPath);
    QVERIFY(def);
    QCOMPARE(AirframeLoader::toJson(*def), AirframeLoader::toJson(Airframe::wellEquipped()));
}

void TestAirframe::shippedFilesMatchTheBuiltIns()
{
    const QDir dir(QStringLiteral(RCM_SOURCE_DIR "/resources/airframes"));
    for (const QString& f : dir.entryList({"*.json"})) {
        QString error;
        const auto fromFile = AirframeLoader::load(dir.filePath(f), &error);
        QVERIFY2(fromFile, qPrintable(error));
        const auto builtIn = AirframeLoader::load(":/airframes/" + f, &error);
        QVERIFY2(builtIn, qPrintable(error));
        QCOMPARE(AirframeLoader::toJson(*fromFile), AirframeLoader::toJson(*builtIn));
    }
}

void TestAirframe::errorsSayWhatAndWhere_data()
{
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("error");
    QTest::newRow("not json") << QByteArray("{\"name\": ") << "a.json: line 1";
    QTest::newRow("array") << QByteArray("[]") << "a.json: an airframe is a JSON object";
    QTest::newRow("typo") << QByteArray(R"({"name": "A", "engine": []})")
                          << "a.json: unknown member \"engine\" (known: name, engines, radios, cameras, senseAndAvoid)";
    QTest::newRow("engine id") << QByteArray(R"({"name": "A", "engines": [{"id": 1}, {"id": 300}]})")
                               << "a.json: engines[1]: \"id\" must be a whole number 0..255";
    QTest::newRow("engine twice") << QByteArray(R"({"name": "A", "engines": [{"id": 2}, {"id": 2}]})")
                                  << "a.json: engines[1]: engine 2 is listed twice";
    QTest::newRow("radio id") << QByteArray(R"({"name": "A", "radios": [{"systemId": "TOOLONGID"}]})")
                              << "a.json: radios[0]: \"systemId\" must be 1 to 8 printable ASCII characters";
    QTest::newRow("camera maker") << QByteArray(R"({"name": "A", "cameras": [{"maker": "NIKON", "number": 1}]})")
                                  << "a.json: cameras[0]: \"maker\" must be 3 printable ASCII characters";
    QTest::newRow("camera number") << QByteArray(R"({"name": "A", "cameras": [{"maker": "NIK"}]})")
                                   << "a.json: cameras[0]: \"number\" must be a whole number 0..255";
    QByteArray many = R"({"name": "A", "radios": [)";
    for (int i = 0; i < 10; ++i)
        many += (i ? "," : "") + QByteArray(R"({"systemId": "R)") + QByteArray::number(i) + "\"}";
    QTest::newRow("does not fit") << many + "]}" << "a.json: these units do not fit in one message: ";
}

void TestAirframe::errorsSayWhatAndWhere()
{
    QFETCH(QByteArray, json);
    QFETCH(QString, error);
    QString got;
    QVERIFY(!AirframeLoader::fromJson(json, "a.json", &got));
    QVERIFY2(got.startsWith(error), qPrintable(got));
}

QTEST_APPLESS_MAIN(TestAirframe)
#include "tst_airframe.moc"
