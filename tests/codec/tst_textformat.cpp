// The text format (codec/message/TextFormat.h) and the country table
// (codec/message/CountryCodes.h): the source document's examples, the shared sample
// frames, random round trips and every parser error.
#include "codec/message/CountryCodes.h"
#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"

#include "RandomMessage.h"

#include <QFile>
#include <QtTest>

#include <random>
#include <string>

using namespace rcm;

namespace {

QByteArray q(const std::string& s) { return QByteArray::fromStdString(s); }

std::string dump(const Diagnostics& ds)
{
    std::string out;
    for (const Diagnostic& d : ds)
        out += d.toString() + "\n";
    return out;
}

QByteArray hexOf(const std::uint8_t* p, std::size_t n)
{
    return QByteArray(reinterpret_cast<const char*>(p), static_cast<qsizetype>(n)).toHex(' ').toUpper();
}

QByteArray readVector(const QString& name)
{
    QFile f(QStringLiteral(RCM_VECTORS_DIR "/rcm/") + name);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return f.readAll();
}

ParseResult parseOrFail(const std::string& text)
{
    ParseResult r = parseMessage(text);
    if (!r.ok())
        qWarning("%s", dump(r.errors).c_str());
    return r;
}

// The canonical text: comments, trailing spaces and blank lines dropped.
std::string stripComments(const std::string& text)
{
    std::string out;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos)
            end = text.size();
        std::string line = text.substr(pos, end - pos);
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
        while (!line.empty() && line.back() == ' ')
            line.pop_back();
        if (!line.empty())
            out += line + "\n";
        pos = end + 1;
    }
    return out;
}

const char* const kSeedExampleText = "BEGIN HEADER\n"
                                     "ID_msg 133\n"
                                     "ID_UA_source GB_133\n"
                                     "time_UTC 16:35:23\n"
                                     "date_UTC 071114\n"
                                     "ID_BLK12_format 5 15\n"
                                     "ID_GCS_destination GB_30226\n"
                                     "ID_GCS_backup GB_41251\n"
                                     "END\n"
                                     "BEGIN SENSE\n"
                                     "SA_zoom_LHS_cam 35\n"
                                     "SA_zoom_FWD_cam 105\n"
                                     "SA_zoom_RHS_cam 35\n"
                                     "END\n";

// The example of TextFormat.h, comments and all.
const char* const kDocumentExample = R"(# a comment runs to the end of the line; blank lines are ignored
BEGIN HEADER
ID_msg 133
ID_UA_source GB_133          # country as ISO alpha-2 or dialling code: 44_133 is the same
time_UTC 16:35:23
date_UTC 071114              # yymmdd as the source document writes it
ID_BLK12_format 5 15
ID_GCS_destination GB_30226
ID_GCS_backup GB_41251
END

BEGIN FCU
BEGIN engine
eng_ID 1
eng_status control=GCS slave=NO_SLAVE
eng_prop_pitch 228
eng_carb_SET 136
END
BEGIN flaps
FLAP_status control=GCS slave_aileron=NO_SLAVE
F_aileron_LHS_set 121
F_aileron_RHS_set -19
END
BEGIN FCU_general
ENABLE_fuel_dump facility=DISABLED tank1=NO_DUMP tank2=NO_DUMP tank3=DUMP
END
END
BEGIN SETTINGS
land_wheels LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT
lights wing_RHS=ON wing_LHS=OFF tail=OFF wheel_brake=ON
setting_72 0x5A
END
BEGIN COMMS
BEGIN comms_system
system_ID VHF1
receiver_control receiver=OFF transmitter=OFF
Rx_freq 127712
Tx_freq 121961
Tx_OP_power 170
END
END
BEGIN SENSE
SA_zoom_LHS_cam 35
SA_zoom_FWD_cam 105
SA_zoom_RHS_cam 35
END
BEGIN PAYLOAD
BEGIN camera
cam_ID SNY 1
cam_mag_compass 264.95
cam_elev -54.64
cam_zoom_set 88
take_one_photo photo=NONE
ID_GCS_destination 1808_49113
ID_GCS_backup 178_57535
END
END
BEGIN FLIGHT_PLAN
flight_plan_ID 0xDEADBEEF
flight_plan_section_ID 3
flight_plan_data 000102030405060708090A0B0C0D0E0F
END
)";

// well-equipped.bin as formatMessage prints it: every kind of value, the
// camera's own stations, a country without an alpha-2 code.
const char* const kWellEquippedText = R"(BEGIN HEADER
ID_msg 4508515
ID_UA_source 1166_8271
time_UTC 08:07:31
date_UTC 970816
ID_BLK12_format 194 107
ID_GCS_destination 193_63944
ID_GCS_backup 59_51093
END
BEGIN FCU
BEGIN engine
eng_ID 1
eng_status control=GCS slave=NO_SLAVE
eng_prop_pitch 228
eng_carb_SET 136
END
BEGIN engine
eng_ID 2
eng_status control=RC slave=NO_SLAVE
eng_prop_pitch 52
eng_carb_SET 162
END
BEGIN engine
eng_ID 3
eng_status control=AUTO slave=NO_SLAVE
eng_prop_pitch 13
eng_carb_SET 4
END
BEGIN flaps
FLAP_status control=GCS slave_aileron=NO_SLAVE
F_aileron_LHS_set 121
F_aileron_RHS_set -19
F_lift_set 58
F_rudder_set -120
F_elev_set 8
F_airbrake_set -71
END
BEGIN FCU_general
ENABLE_fuel_dump facility=DISABLED tank1=NO_DUMP tank2=NO_DUMP tank3=DUMP
END
END
BEGIN SETTINGS
land_wheels LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT
lights wing_RHS=ON wing_LHS=OFF tail=OFF wheel_brake=ON
END
BEGIN COMMS
BEGIN comms_system
system_ID VHF1
receiver_control receiver=OFF transmitter=OFF
Rx_freq 127712
Tx_freq 121961
Tx_OP_power 170
END
BEGIN comms_system
system_ID VHF2
receiver_control receiver=OFF transmitter=OFF
Rx_freq 134410
Tx_freq 131831
Tx_OP_power 97
END
BEGIN comms_system
system_ID VHF3
receiver_control receiver=ON transmitter=OFF
Rx_freq 134363
Tx_freq 134557
Tx_OP_power 201
END
END
BEGIN SENSE
SA_zoom_LHS_cam 17
SA_zoom_FWD_cam 245
SA_zoom_RHS_cam 124
END
BEGIN PAYLOAD
BEGIN camera
cam_ID SNY 1
cam_mag_compass 264.95
cam_elev 45.76
cam_zoom_set 88
take_one_photo photo=NONE
ID_GCS_destination 1808_49113
ID_GCS_backup 178_57535
END
BEGIN camera
cam_ID SNY 2
cam_mag_compass 333.20
cam_elev -54.64
cam_zoom_set 83
take_one_photo photo=NONE
ID_GCS_destination 806_48565
ID_GCS_backup 1003_3876
END
END
)";

}  // namespace

class TestTextFormat : public QObject {
    Q_OBJECT

private slots:
    void seedExamples_data();
    void seedExamples();
    void seedExampleFrameText();
    void vectorFrames_data();
    void vectorFrames();
    void vectorLines_data();
    void vectorLines();
    void documentExample();
    void acceptedForms_data();
    void acceptedForms();
    void placementOutsideSections();
    void canonicalPrinting();
    void randomRoundTrip();
    void parseErrors_data();
    void parseErrors();
    void reportsEveryError();
    void badInput_data();
    void badInput();
    void byteOrderMarkIsSkipped();
    void errorsAreCapped();
    void block1OverflowNamesTheItem();
    void countries_data();
    void countries();
    void countryForCode_data();
    void countryForCode();
    void countryTableConsistent();
    void wellEquippedFrameText();
};

// ---------------------------------------------------------- source examples

void TestTextFormat::seedExamples_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QByteArray>("bytes");  // the item as it ends BLOCK 1
    QTest::newRow("ID_msg") << QByteArray("ID_msg 133") << QByteArray("03 00 00 85");
    QTest::newRow("ID_msg hex") << QByteArray("ID_msg 0x85") << QByteArray("03 00 00 85");
    QTest::newRow("time_UTC") << QByteArray("time_UTC 16:35:23") << QByteArray("05 02 7E C3");
    QTest::newRow("time_UTC hhmmss") << QByteArray("time_UTC 163523") << QByteArray("05 02 7E C3");
    QTest::newRow("date_UTC") << QByteArray("date_UTC 071114") << QByteArray("06 01 15 CA");
    QTest::newRow("ID_BLK12_format") << QByteArray("ID_BLK12_format 5 15") << QByteArray("07 05 0F");
    QTest::newRow("SA_zoom_LHS_cam") << QByteArray("SA_zoom_LHS_cam 35") << QByteArray("B0 23");
    QTest::newRow("ID_UA_source GB") << QByteArray("ID_UA_source GB_133") << QByteArray("04 00 2C 00 85");
    QTest::newRow("ID_UA_source 44") << QByteArray("ID_UA_source 44_133") << QByteArray("04 00 2C 00 85");
    QTest::newRow("ID_UA_source gb") << QByteArray("ID_UA_source gb_133") << QByteArray("04 00 2C 00 85");
    QTest::newRow("ID_GCS_destination") << QByteArray("ID_GCS_destination GB_30226")
                                        << QByteArray("08 00 2C 76 12");
    QTest::newRow("in its section") << QByteArray("BEGIN HEADER\nID_msg 133\nEND\n") << QByteArray("03 00 00 85");
}

void TestTextFormat::seedExamples()
{
    QFETCH(QByteArray, text);
    QFETCH(QByteArray, bytes);
    const ParseResult r = parseOrFail(text.toStdString());
    QVERIFY(r.ok());
    Diagnostics errors;
    const auto blocks = encodeBlocks(r.message, errors);
    QVERIFY2(blocks, dump(errors).c_str());
    const std::size_t n = static_cast<std::size_t>(bytes.count(' ') + 1);
    QCOMPARE(hexOf(blocks->block1.data() + kBlockSize - n, n), bytes);
    for (std::size_t i = 0; i < kBlockSize - n; ++i)
        QCOMPARE(blocks->block1[i], kPad55);
}

void TestTextFormat::seedExampleFrameText()
{
    const QByteArray frame = readVector("seed-example.bin");
    QCOMPARE(frame.size(), qsizetype(kFrameSize));
    const DecodeResult d = decodeFrame(std::span(reinterpret_cast<const std::uint8_t*>(frame.data()), kFrameSize));
    QVERIFY(d.ok());
    QCOMPARE(q(formatMessage(d.message)), QByteArray(kSeedExampleText));
}

// ------------------------------------------------------------ sample frames

void TestTextFormat::vectorFrames_data()
{
    QTest::addColumn<QString>("file");
    QTest::newRow("seed-example") << QStringLiteral("seed-example.bin");
    QTest::newRow("well-equipped") << QStringLiteral("well-equipped.bin");
    QTest::newRow("flight-plan") << QStringLiteral("flight-plan.bin");
}

void TestTextFormat::vectorFrames()
{
    QFETCH(QString, file);
    const QByteArray frame = readVector(file);
    QCOMPARE(frame.size(), qsizetype(kFrameSize));
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(frame.data());
    const DecodeResult d = decodeFrame(std::span(bytes, kFrameSize));
    QVERIFY(d.ok());
    QVERIFY2(d.diagnostics.empty(), dump(d.diagnostics).c_str());

    const std::string text = formatMessage(d.message);
    const ParseResult r = parseOrFail(text);
    QVERIFY(r.ok());
    QVERIFY(r.message == d.message);
    QCOMPARE(q(formatMessage(r.message)), q(text));

    Diagnostics errors;
    const auto again = encodeFrame(r.message, errors);
    QVERIFY2(again, dump(errors).c_str());
    QCOMPARE(hexOf(again->data(), kFrameSize), hexOf(bytes, kFrameSize));
}

void TestTextFormat::vectorLines_data()
{
    QTest::addColumn<QString>("file");
    QTest::addColumn<QByteArray>("line");
    auto row = [](const char* name, const char* file, const char* line) {
        QTest::newRow(name) << QString::fromLatin1(file) << QByteArray(line);
    };
    row("eng_status D0", "flight-plan.bin", "eng_status control=RC slave=NO_SLAVE");
    row("eng_status 90", "well-equipped.bin", "eng_status control=GCS slave=NO_SLAVE");
    row("F_aileron_RHS_set ED", "well-equipped.bin", "F_aileron_RHS_set -19");
    row("cam_elev EA A8", "well-equipped.bin", "cam_elev -54.64");
    row("cam_mag_compass 67 7F", "well-equipped.bin", "cam_mag_compass 264.95");
    row("system_ID", "well-equipped.bin", "system_ID VHF1");
    row("take_one_photo 40", "well-equipped.bin", "take_one_photo photo=NONE");
    row("station without a country", "well-equipped.bin", "ID_UA_source 1166_8271");
    row("camera destination", "well-equipped.bin", "ID_GCS_destination 1808_49113");
    row("station 90 = TR", "flight-plan.bin", "ID_UA_source TR_40439");
    row("land_wheels 55", "flight-plan.bin", "land_wheels LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT");
    row("flight_plan_ID", "flight-plan.bin", "flight_plan_ID 0xDEADBEEF");
    row("flight_plan_section_ID", "flight-plan.bin", "flight_plan_section_ID 3");
    row("flight_plan_data", "flight-plan.bin",
        "flight_plan_data 000102030405060708090A0B0C0D0E0F101112131415161718191A1B1C1D1E1F2021222324252627");
}

void TestTextFormat::vectorLines()
{
    QFETCH(QString, file);
    QFETCH(QByteArray, line);
    const QByteArray frame = readVector(file);
    QCOMPARE(frame.size(), qsizetype(kFrameSize));
    const DecodeResult d =
        decodeFrame(std::span(reinterpret_cast<const std::uint8_t*>(frame.data()), kFrameSize));
    const QByteArray text = q(formatMessage(d.message));
    QVERIFY2(text.split('\n').contains(line), text.constData());
}

void TestTextFormat::documentExample()
{
    const ParseResult r = parseOrFail(kDocumentExample);
    QVERIFY(r.ok());
    const Message& m = r.message;
    QCOMPARE(m.header.find(ItemId::ID_UA_source)->number, 44);
    QCOMPARE(m.header.find(ItemId::ID_UA_source)->second, 133);
    QCOMPARE(m.header.find(ItemId::ID_GCS_destination)->second, 30226);
    QCOMPARE(m.engines.size(), std::size_t(1));
    QCOMPARE(m.engines[0].number(ItemId::eng_prop_pitch), 228);
    QCOMPARE(m.flaps.number(ItemId::F_aileron_RHS_set), -19);
    QCOMPARE(m.settings.number(ItemId::setting_72), 0x5A);
    QCOMPARE(m.radios.size(), std::size_t(1));
    QCOMPARE(m.radios[0].find(ItemId::system_ID)->text, std::string("VHF1"));
    QCOMPARE(m.radios[0].number(ItemId::Rx_freq), 127712);
    QCOMPARE(m.cameras.size(), std::size_t(1));
    QCOMPARE(m.cameras[0].number(ItemId::cam_mag_compass), 26495);
    QCOMPARE(m.cameras[0].number(ItemId::cam_elev), -5464);
    QCOMPARE(m.cameras[0].find(ItemId::cam_GCS_destination)->number, 1808);
    QCOMPARE(m.flightPlan.planId, 0xDEADBEEFu);
    QCOMPARE(m.flightPlan.data.size(), std::size_t(16));
    // The example is canonical apart from its comments and blank line.
    QCOMPARE(q(formatMessage(m)), q(stripComments(kDocumentExample)));
    Diagnostics errors;
    QVERIFY2(encodeFrame(m, errors), dump(errors).c_str());
}

// ------------------------------------------------------- what the parser takes

void TestTextFormat::acceptedForms_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QByteArray>("canonical");
    auto row = [](const char* name, const char* text, const char* canonical) {
        QTest::newRow(name) << QByteArray(text) << QByteArray(canonical);
    };
    const char* const cam = "BEGIN PAYLOAD\nBEGIN camera\ncam_ID NIK 1\n";
    const std::string camEnd = "END\nEND\n";
    auto camRow = [&](const char* name, const char* line, const char* printed) {
        QTest::newRow(name) << QByteArray((std::string("cam_ID NIK 1\n") + line).c_str())
                            << QByteArray((std::string(cam) + printed + "\n" + camEnd).c_str());
    };
    camRow("one decimal", "cam_mag_compass 264.9", "cam_mag_compass 264.90");
    camRow("no decimals", "cam_elev -54", "cam_elev -54.00");
    camRow("below one", "cam_elev -0.5", "cam_elev -0.50");
    camRow("hundredths", "cam_elev -0.05", "cam_elev -0.05");
    camRow("zero", "cam_mag_compass 0", "cam_mag_compass 0.00");
    camRow("hex zoom", "cam_zoom_set 0x10", "cam_zoom_set 16");
    row("hex integer", "ID_msg 0X85", "BEGIN HEADER\nID_msg 133\nEND\n");
    row("time as hhmmss", "time_UTC 5", "BEGIN HEADER\ntime_UTC 00:00:05\nEND\n");
    row("country lower case", "ID_UA_source gb_133", "BEGIN HEADER\nID_UA_source GB_133\nEND\n");
    row("NANP member", "ID_UA_source pr_5", "BEGIN HEADER\nID_UA_source US_5\nEND\n");
    row("country as number", "ID_UA_source 1_5", "BEGIN HEADER\nID_UA_source US_5\nEND\n");
    row("country in hex", "ID_UA_source 0x2C_0x85", "BEGIN HEADER\nID_UA_source GB_133\nEND\n");
    row("fields as a byte", "eng_ID 1\neng_status 0x90",
        "BEGIN FCU\nBEGIN engine\neng_ID 1\neng_status control=GCS slave=NO_SLAVE\nEND\nEND\n");
    row("fields in any order", "eng_ID 1\neng_status slave=MASTER_SLAVE control=AUTO",
        "BEGIN FCU\nBEGIN engine\neng_ID 1\neng_status control=AUTO slave=MASTER_SLAVE\nEND\nEND\n");
    row("raw setting", "setting_72 90", "BEGIN SETTINGS\nsetting_72 0x5A\nEND\n");
    row("quoted text", "system_ID \"VHF 1\"", "BEGIN COMMS\nBEGIN comms_system\nsystem_ID \"VHF 1\"\nEND\nEND\n");
    row("needless quotes", "system_ID \"A\\x42C\"", "BEGIN COMMS\nBEGIN comms_system\nsystem_ID ABC\nEND\nEND\n");
    row("escapes", "system_ID \"a\\\"b\\\\c#\"",
        "BEGIN COMMS\nBEGIN comms_system\nsystem_ID \"a\\\"b\\\\c#\"\nEND\nEND\n");
    row("backslash bare", "system_ID a\\b", "BEGIN COMMS\nBEGIN comms_system\nsystem_ID a\\b\nEND\nEND\n");
    row("lower-case data", "flight_plan_ID 5\nflight_plan_data 0a0b",
        "BEGIN FLIGHT_PLAN\nflight_plan_ID 0x00000005\nflight_plan_section_ID 0\nflight_plan_data 0A0B\nEND\n");
    row("empty flight plan", "flight_plan_ID 0\nflight_plan_section_ID 0", "");
    row("CRLF, tabs, comments", "  ID_msg\t133   # the counter\r\n\r\n# nothing\r\nSA_zoom_LHS_cam 1#c\r\n",
        "BEGIN HEADER\nID_msg 133\nEND\nBEGIN SENSE\nSA_zoom_LHS_cam 1\nEND\n");
    row("child section at top level", "BEGIN engine\neng_ID 2\nEND",
        "BEGIN FCU\nBEGIN engine\neng_ID 2\nEND\nEND\n");
    row("key anywhere in its section", "BEGIN engine\neng_carb_SET 3\neng_ID 2\nEND",
        "BEGIN FCU\nBEGIN engine\neng_ID 2\neng_carb_SET 3\nEND\nEND\n");
    row("empty text", "", "");
}

void TestTextFormat::acceptedForms()
{
    QFETCH(QByteArray, text);
    QFETCH(QByteArray, canonical);
    const ParseResult r = parseOrFail(text.toStdString());
    QVERIFY(r.ok());
    QCOMPARE(q(formatMessage(r.message)), canonical);
}

void TestTextFormat::placementOutsideSections()
{
    const ParseResult r = parseOrFail("eng_ID 1\n"
                                      "eng_prop_pitch 10\n"
                                      "eng_ID 2\n"
                                      "eng_prop_pitch 20\n"
                                      "BEGIN engine\n"
                                      "eng_ID 3\n"
                                      "END\n"
                                      "eng_carb_SET 30\n"  // the last engine started: 3
                                      "ID_GCS_destination GB_1\n"  // the header's
                                      "BEGIN camera\n"
                                      "cam_ID NIK 1\n"
                                      "ID_GCS_destination FR_2\n"  // the camera's
                                      "END\n"
                                      "cam_zoom_set 7\n"
                                      "system_ID R1\n"
                                      "Rx_freq 100\n"
                                      "flight_plan_section_ID 9\n");
    QVERIFY(r.ok());
    const Message& m = r.message;
    QCOMPARE(m.engines.size(), std::size_t(3));
    QCOMPARE(m.engines[0].number(ItemId::eng_prop_pitch), 10);
    QCOMPARE(m.engines[1].number(ItemId::eng_prop_pitch), 20);
    QVERIFY(!m.engines[2].has(ItemId::eng_prop_pitch));
    QCOMPARE(m.engines[2].number(ItemId::eng_carb_SET), 30);
    QCOMPARE(m.header.find(ItemId::ID_GCS_destination)->number, 44);
    QCOMPARE(m.cameras.size(), std::size_t(1));
    QCOMPARE(m.cameras[0].find(ItemId::cam_GCS_destination)->number, 33);
    QCOMPARE(m.cameras[0].number(ItemId::cam_zoom_set), 7);
    QCOMPARE(m.radios.size(), std::size_t(1));
    QCOMPARE(m.radios[0].number(ItemId::Rx_freq), 100);
    QCOMPARE(m.flightPlan.sectionId, std::uint16_t(9));
}

void TestTextFormat::canonicalPrinting()
{
    Message m;
    m.header.set(ItemId::ID_UA_source, Value::station({1166, 8271}));
    m.header.set(ItemId::ID_GCS_destination, Value::station({1, 5}));
    m.header.set(ItemId::ID_GCS_backup, Value::station({7, 0}));
    m.header.set(ItemId::date_UTC, 10101);
    m.header.set(ItemId::time_UTC, 905);
    m.addEngine(1).set(ItemId::eng_status, 0x91);  // reserved bits set
    m.settings.set(ItemId::land_wheels, 0x55);
    m.settings.set(ItemId::lights, 0x00);  // every field corrupt
    m.settings.set(ItemId::setting_72, 0x05);
    m.addRadio("A B");
    m.addRadio("x#\"\\");
    m.addRadio("");
    m.addRadio("A\x01");
    m.addCamera("N K", 2);
    m.flightPlan.sectionId = 7;  // not empty, but no data

    const std::string expected = "BEGIN HEADER\n"
                                 "ID_UA_source 1166_8271\n"
                                 "time_UTC 00:09:05\n"
                                 "date_UTC 010101\n"
                                 "ID_GCS_destination US_5\n"
                                 "ID_GCS_backup RU_0\n"
                                 "END\n"
                                 "BEGIN FCU\n"
                                 "BEGIN engine\n"
                                 "eng_ID 1\n"
                                 "eng_status 0x91\n"
                                 "END\n"
                                 "END\n"
                                 "BEGIN SETTINGS\n"
                                 "land_wheels LHS=OUT RHS=OUT NOSE=OUT TAIL=OUT\n"
                                 "lights 0x00\n"
                                 "setting_72 0x05\n"
                                 "END\n"
                                 "BEGIN COMMS\n"
                                 "BEGIN comms_system\n"
                                 "system_ID \"A B\"\n"
                                 "END\n"
                                 "BEGIN comms_system\n"
                                 "system_ID \"x#\\\"\\\\\"\n"
                                 "END\n"
                                 "BEGIN comms_system\n"
                                 "system_ID \"\"\n"
                                 "END\n"
                                 "BEGIN comms_system\n"
                                 "system_ID \"A\\x01\"\n"
                                 "END\n"
                                 "END\n"
                                 "BEGIN PAYLOAD\n"
                                 "BEGIN camera\n"
                                 "cam_ID \"N K\" 2\n"
                                 "END\n"
                                 "END\n"
                                 "BEGIN FLIGHT_PLAN\n"
                                 "flight_plan_ID 0x00000000\n"
                                 "flight_plan_section_ID 7\n"
                                 "END\n";
    const std::string text = formatMessage(m);
    QCOMPARE(q(text), q(expected));

    // The bytes no name can stand for come back as they were, and are refused
    // for what they are, on the lines that hold them.
    const ParseResult r = parseMessage(text);
    QCOMPARE(r.errors.size(), std::size_t(3));
    QCOMPARE(r.errors[0].line, 11);
    QCOMPARE(r.errors[0].kind, Diagnostic::Kind::OutOfRange);
    QVERIFY(r.errors[0].message.find("reserved bits") != std::string::npos);
    QCOMPARE(r.errors[1].line, 16);
    QVERIFY(r.errors[1].message.find("data corruption") != std::string::npos);
    QCOMPARE(r.errors[2].line, 30);
    QVERIFY(r.errors[2].message.find("printable ASCII") != std::string::npos);

    // Without them the message is valid and reads back exactly.
    m.engines[0].set(ItemId::eng_status, 0x90);
    m.settings.set(ItemId::lights, 0x55);
    m.radios.pop_back();
    const std::string valid = formatMessage(m);
    const ParseResult v = parseOrFail(valid);
    QVERIFY(v.ok());
    QVERIFY(v.message == m);
    QCOMPARE(q(formatMessage(v.message)), q(valid));
}

void TestTextFormat::randomRoundTrip()
{
    std::mt19937_64 rng(20240611);
    for (int i = 0; i < 5000; ++i) {
        const Message m = test::randomMessage(rng);
        const std::string text = formatMessage(m);

        // text -> model -> text
        const ParseResult r = parseMessage(text);
        QVERIFY2(r.ok(), (std::to_string(i) + ":\n" + text + dump(r.errors)).c_str());
        QVERIFY2(r.message == m, (std::to_string(i) + ": parsed message differs:\n" + text).c_str());
        const std::string again = formatMessage(r.message);
        QVERIFY2(again == text, (std::to_string(i) + ":\n" + text + "---\n" + again).c_str());

        // binary -> text -> binary
        Diagnostics errors;
        const auto frame = encodeFrame(m, errors);
        QVERIFY2(frame, (std::to_string(i) + ": " + dump(errors)).c_str());
        const DecodeResult d = decodeFrame(*frame);
        QVERIFY2(d.ok() && d.diagnostics.empty(), dump(d.diagnostics).c_str());
        QVERIFY2(d.message == m, (std::to_string(i) + ": decoded message differs:\n" + text).c_str());
        const ParseResult back = parseMessage(formatMessage(d.message));
        QVERIFY(back.ok());
        const auto frame2 = encodeFrame(back.message, errors);
        QVERIFY(frame2);
        QVERIFY2(*frame2 == *frame, std::to_string(i).c_str());
    }
}

// ------------------------------------------------------------------ errors

void TestTextFormat::parseErrors_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<int>("line");
    QTest::addColumn<int>("column");
    QTest::addColumn<bool>("outOfRange");
    QTest::addColumn<QByteArray>("message");  // a part of the message
    auto syntax = [](const char* name, const QByteArray& text, int line, int column, const char* message) {
        QTest::newRow(name) << text << line << column << false << QByteArray(message);
    };
    auto range = [](const char* name, const QByteArray& text, int line, int column, const char* message) {
        QTest::newRow(name) << text << line << column << true << QByteArray(message);
    };
    const QByteArray engine = "BEGIN engine\neng_ID 1\n";

    // names and structure
    syntax("unknown item", "foo 1", 1, 1, "unknown item 'foo'");
    syntax("name case", "id_msg 1", 1, 1, "names are case-sensitive: ID_msg");
    syntax("item of another section", engine + "ID_msg 1\nEND", 3, 1,
           "'ID_msg' is not an item of section engine; section engine (BEGIN at line 1) holds only the items "
           "eng_ID, eng_status, eng_prop_pitch and eng_carb_SET");
    syntax("unknown item in a section", engine + "  bar 1\nEND", 3, 3,
           "unknown item 'bar'; section engine (BEGIN at line 1) holds only the items");
    syntax("plan item in a unit", engine + "flight_plan_ID 1\nEND", 3, 1,
           "'flight_plan_ID' is not an item of section engine");
    syntax("item in FLIGHT_PLAN", "BEGIN FLIGHT_PLAN\nID_msg 1\nEND", 2, 1,
           "'ID_msg' is not an item of section FLIGHT_PLAN; section FLIGHT_PLAN holds only the items "
           "flight_plan_ID, flight_plan_section_ID and flight_plan_data");
    syntax("unknown section", "BEGIN foo\nEND", 1, 7, "unknown section 'foo'; expected HEADER, FCU, engine,");
    syntax("section case", "BEGIN Header\nEND", 1, 7, "names are case-sensitive: HEADER");
    syntax("unknown child section", "BEGIN COMMS\nBEGIN radio\nEND\nEND", 2, 7,
           "unknown section 'radio'; expected comms_system inside section COMMS");
    syntax("child in the wrong parent", "BEGIN FCU\nBEGIN camera\ncam_ID NIK 1\nEND\nEND", 2, 7,
           "section camera cannot be inside section FCU: section FCU holds only its sections engine, flaps and "
           "FCU_general; camera belongs inside section PAYLOAD or at the top level");
    syntax("section in a unit", "BEGIN HEADER\nBEGIN SENSE\nEND\nEND", 2, 7,
           "section SENSE cannot be inside section HEADER");
    syntax("parent in a parent", "BEGIN FCU\nBEGIN FCU\nEND\nEND", 2, 7,
           "section FCU cannot be inside section FCU");
    syntax("FLIGHT_PLAN in a parent", "BEGIN FCU\nBEGIN FLIGHT_PLAN\nEND\nEND", 2, 7,
           "FLIGHT_PLAN belongs at the top level");
    syntax("item in a parent", "BEGIN FCU\neng_ID 1\nEND", 2, 1,
           "section FCU holds only its sections engine, flaps and FCU_general; put 'eng_ID' inside one of them");
    syntax("BEGIN without a name", "BEGIN\nEND", 1, 7, "BEGIN needs a section name: HEADER, FCU,");
    syntax("BEGIN with two names", "BEGIN HEADER extra\nEND", 1, 14, "BEGIN takes one section name");
    syntax("END with a name", "BEGIN HEADER\nEND HEADER", 2, 5, "END takes nothing after it");
    syntax("END without BEGIN", "ID_msg 1\nEND", 2, 1, "END without a BEGIN to close");
    syntax("unclosed section", "BEGIN HEADER\nID_msg 1\n", 1, 1, "section HEADER opened at line 1 has no END");
    syntax("unclosed parent", "\n  BEGIN FCU\nBEGIN engine\neng_ID 1\nEND\n", 2, 3,
           "section FCU opened at line 2 has no END");
    syntax("engine without its key", "BEGIN engine\neng_prop_pitch 3\nEND", 3, 1,
           "section engine (BEGIN at line 1) ends without its key item eng_ID");
    syntax("camera without its key", "BEGIN PAYLOAD\nBEGIN camera\ncam_zoom_set 1\n END\nEND", 4, 2,
           "ends without its key item cam_ID");
    syntax("item before its key", "eng_prop_pitch 3", 1, 1,
           "eng_prop_pitch comes before any eng_ID: put it after eng_ID or inside BEGIN engine ... END");
    syntax("camera item before its key", "ID_GCS_backup GB_1\ncam_zoom_set 5", 2, 1,
           "cam_zoom_set comes before any cam_ID");
    syntax("item twice", "ID_msg 1\nID_msg 2", 2, 1, "ID_msg is given twice in HEADER; first at line 1");
    syntax("key twice in a section", engine + "eng_ID 2\nEND", 3, 1,
           "eng_ID is given twice in engine 1; first at line 2");
    syntax("single unit in two sections", "BEGIN SENSE\nSA_zoom_LHS_cam 1\nEND\nBEGIN SENSE\nSA_zoom_LHS_cam 2\nEND",
           5, 1, "first at line 2");
    syntax("plan item twice", "flight_plan_ID 1\nflight_plan_ID 2", 2, 1,
           "flight_plan_ID is given twice; first at line 1");
    syntax("quoted item name", "\"ID_msg\" 1", 1, 1, "expected an item name, BEGIN or END");

    // tokens
    syntax("no closing quote", "system_ID \"ABC", 1, 11, "quoted text has no closing \"");
    syntax("unknown escape", "system_ID \"A\\qB\"", 1, 13, "unknown escape in quoted text");
    syntax("short hex escape", "system_ID \"A\\x4\"", 1, 13, "\\xHH (two hex digits)");
    syntax("text after a quote", "system_ID \"AB\"C", 1, 15, "expected a space after the closing \"");
    syntax("quote inside a token", "system_ID A\"B", 1, 12, "a \" may only start a value");

    // value counts and numbers
    syntax("missing value", "ID_msg", 1, 8, "ID_msg needs a value: an integer from 0 to 16777215");
    syntax("missing second value", "ID_BLK12_format 5", 1, 19,
           "ID_BLK12_format needs another value: two integers from 0 to 255");
    syntax("extra value", "ID_msg 1 2", 1, 10, "unexpected '2' after the value: ID_msg takes an integer");
    syntax("bad number", "ID_msg 12x", 1, 8, "expected an integer from 0 to 16777215 (decimal or 0x hex), got '12x'");
    syntax("bare 0x", "ID_msg 0x", 1, 8, "got '0x'");
    syntax("quoted number", "ID_msg \"1\"", 1, 8, "got quoted text \"1\"");
    range("above the maximum", "ID_msg 16777216", 1, 8, "16777216 is above the maximum 16777215 by 1");
    range("below the minimum", "ID_msg -1", 1, 8, "-1 is below the minimum 0 by 1");
    range("past 64 bits", "ID_msg 99999999999999999999", 1, 8, "'99999999999999999999' does not fit in 64 bits");
    range("signed", "F_elev_set -128", 1, 12, "-128 is below the minimum -127 by 1");
    syntax("too many decimals", "cam_ID NIK 1\ncam_elev 1.234", 2, 10,
           "cam_elev takes at most 2 decimals (it is sent in units of 1/100), got '1.234'");
    syntax("hex for hundredths", "cam_ID NIK 1\ncam_mag_compass 0x10", 2, 17,
           "expected a number from 0.00 to 359.99 with at most 2 decimals, got '0x10'");
    syntax("dot without decimals", "cam_ID NIK 1\ncam_elev 1.", 2, 10, "got '1.'");
    range("hundredths above the maximum", "cam_ID NIK 1\ncam_mag_compass 360", 2, 17,
          "360.00 is above the maximum 359.99 by 0.01");
    range("raw byte", "setting_72 0x100", 1, 12, "value 256 is above the maximum 255 by 1");

    // two-bit fields
    syntax("unknown field", engine + "eng_status ctrl=GCS slave=NO_SLAVE\nEND", 3, 12,
           "eng_status has no field 'ctrl'; its fields are control and slave");
    syntax("unknown code", engine + "eng_status control=XYZ slave=NO_SLAVE\nEND", 3, 20,
           "field control takes AUTO, GCS or RC, not 'XYZ'");
    syntax("missing field", engine + "eng_status control=GCS\nEND", 3, 24,
           "eng_status is missing field slave (NO_SLAVE or MASTER_SLAVE)");
    syntax("field twice", engine + "eng_status control=GCS control=RC slave=NO_SLAVE\nEND", 3, 24,
           "field control is given twice");
    syntax("field without a code", engine + "eng_status control=GCS NO_SLAVE\nEND", 3, 24,
           "expected FIELD=CODE, got 'NO_SLAVE'; eng_status takes every field as FIELD=CODE "
           "(control=AUTO|GCS|RC slave=NO_SLAVE|MASTER_SLAVE), or the byte as 0xNN");
    range("corrupt byte", "BEGIN flaps\nFLAP_status 0x00\nEND", 2, 13,
          "field control: code 00 means data corruption");

    // stations, time, date
    syntax("unknown country", "ID_UA_source XX_1", 1, 14, "unknown country 'XX': expected an ISO 3166-1 alpha-2");
    syntax("station without unit", "ID_UA_source 44", 1, 14, "expected a station COUNTRY_UNIT such as GB_133");
    syntax("bad country", "ID_UA_source G1_5", 1, 14, "expected a country before '_'");
    syntax("bad unit", "ID_UA_source GB_x", 1, 17, "expected a unit number after '_', got 'x'");
    range("country out of range", "ID_UA_source 0_1", 1, 14, "country dialling code 0 is below the minimum 1 by 1");
    range("unit out of range", "ID_UA_source GB_65536", 1, 14, "unit number 65536 is above the maximum 65535 by 1");
    syntax("bad time", "time_UTC 16:35", 1, 10, "expected a time hh:mm:ss such as 16:35:23, or hhmmss");
    range("minutes", "time_UTC 16:61:00", 1, 10, "minutes 61 is above the maximum 59 by 2");
    syntax("date not 6 digits", "date_UTC 71114", 1, 10, "expected a date yymmdd of 6 digits");
    range("day", "date_UTC 071131", 1, 10, "day 31 is above the maximum 30 by 1");

    // text, camera, format pair
    range("text too long", "system_ID ABCDEFGHI", 1, 11, "9 characters, 1 more than the 8 allowed");
    range("camera number", "cam_ID NIK 256", 1, 12, "camera number 256 is above the maximum 255 by 1");
    range("maker length", "cam_ID NI 1", 1, 8, "maker must be exactly 3 printable ASCII characters");
    range("first format ID", "ID_BLK12_format 256 5", 1, 17, "first format ID 256 is above the maximum 255 by 1");
    range("second format ID", "ID_BLK12_format 5 256", 1, 19, "second format ID 256 is above the maximum 255 by 1");

    // flight plan
    syntax("odd hex digits", "flight_plan_data ABC", 1, 18, "an odd number of hex digits (3)");
    syntax("not hex", "flight_plan_data 0G", 1, 19, "'G' is not a hex digit");
    range("too much data", "flight_plan_data " + QByteArray(432, 'A'), 1, 18,
          "216 bytes is above the maximum 215 by 1");
    range("plan ID", "flight_plan_ID 0x100000000", 1, 16, "4294967296 is above the maximum 4294967295 by 1");
    range("plan section ID", "flight_plan_section_ID 65536", 1, 24, "65536 is above the maximum 65535 by 1");
}

void TestTextFormat::parseErrors()
{
    QFETCH(QByteArray, text);
    QFETCH(int, line);
    QFETCH(int, column);
    QFETCH(bool, outOfRange);
    QFETCH(QByteArray, message);
    const ParseResult r = parseMessage(text.toStdString());
    QVERIFY(!r.ok());
    QVERIFY2(r.errors.size() == 1, dump(r.errors).c_str());
    const Diagnostic& e = r.errors.front();
    QVERIFY2(e.message.find(message.toStdString()) != std::string::npos, e.message.c_str());
    QCOMPARE(e.line, line);
    QCOMPARE(e.column, column);
    QCOMPARE(e.kind, outOfRange ? Diagnostic::Kind::OutOfRange : Diagnostic::Kind::Syntax);
    QCOMPARE(e.block, 0);
}

void TestTextFormat::reportsEveryError()
{
    const ParseResult r = parseMessage("ID_msg 1x\n"
                                       "time_UTC 12:00:00\n"
                                       "foo 3\n"
                                       "BEGIN SENSE\n"
                                       "SA_zoom_LHS_cam 300\n"
                                       "END\n"
                                       "ID_BLK12_format 256 -1\n"
                                       "date_UTC 071114\n"
                                       "BEGIN camera\n");
    QVERIFY(!r.ok());
    // One error for line 7: a value is refused for its first problem.
    QCOMPARE(r.errors.size(), std::size_t(5));
    const int expected[][2] = {{1, 8}, {3, 1}, {5, 17}, {7, 17}, {9, 1}};
    for (std::size_t i = 0; i < r.errors.size(); ++i) {
        QCOMPARE(r.errors[i].line, expected[i][0]);
        QCOMPARE(r.errors[i].column, expected[i][1]);
    }
    QVERIFY(r.errors[2].message.find("300 is above the maximum 255 by 45") != std::string::npos);
    QVERIFY(r.errors[3].message.find("first format ID 256") != std::string::npos);
    QVERIFY(r.errors[4].message.find("section camera opened at line 9 has no END") != std::string::npos);
    // The lines around them were read.
    QCOMPARE(r.message.header.number(ItemId::time_UTC), 120000);
    QCOMPARE(r.message.header.number(ItemId::date_UTC), 71114);
    QVERIFY(!r.message.header.has(ItemId::ID_msg));
}

// ---------------------------------------------------------------- countries

void TestTextFormat::countries_data()
{
    QTest::addColumn<QByteArray>("alpha2");
    QTest::addColumn<int>("code");  // -1: none
    const std::pair<const char*, int> rows[] = {
        {"GB", 44}, {"gb", 44}, {"gB", 44}, {"US", 1},   {"CA", 1},  {"PR", 1},   {"JM", 1},  {"DE", 49},
        {"FR", 33}, {"RU", 7},  {"KZ", 7},  {"AU", 61},  {"IN", 91}, {"JP", 81},  {"CN", 86}, {"BR", 55},
        {"ZA", 27}, {"NZ", 64}, {"VA", 39}, {"GG", 44},  {"SJ", 47}, {"EH", 212}, {"YT", 262}, {"CW", 599},
        {"XX", -1}, {"", -1},   {"G", -1},  {"GBR", -1}, {"G1", -1}, {"BV", -1},  {"UM", -1},
    };
    for (const auto& [alpha2, code] : rows)
        QTest::newRow(*alpha2 ? alpha2 : "empty") << QByteArray(alpha2) << code;
}

void TestTextFormat::countries()
{
    QFETCH(QByteArray, alpha2);
    QFETCH(int, code);
    const auto found = diallingCodeForCountry(std::string_view(alpha2.constData(), alpha2.size()));
    QCOMPARE(found ? int(*found) : -1, code);
}

void TestTextFormat::countryForCode_data()
{
    QTest::addColumn<int>("code");
    QTest::addColumn<QByteArray>("alpha2");
    const std::pair<int, const char*> rows[] = {
        {1, "US"},   {7, "RU"},   {44, "GB"},  {47, "NO"},  {61, "AU"}, {39, "IT"},  {64, "NZ"},
        {212, "MA"}, {262, "RE"}, {290, "SH"}, {358, "FI"}, {500, "FK"}, {590, "GP"}, {599, "CW"},
        {672, "NF"}, {49, "DE"},  {998, "UZ"}, {999, ""},   {0, ""},    {1166, ""},  {1929, ""},
    };
    for (const auto& [code, alpha2] : rows)
        QTest::newRow(std::to_string(code).c_str()) << code << QByteArray(alpha2);
}

void TestTextFormat::countryForCode()
{
    QFETCH(int, code);
    QFETCH(QByteArray, alpha2);
    const std::string_view found = countryForDiallingCode(static_cast<std::uint16_t>(code));
    QCOMPARE(QByteArray(found.data(), qsizetype(found.size())), alpha2);
}

void TestTextFormat::countryTableConsistent()
{
    // Every printed country reads back to its code: stations round-trip.
    for (int code = 0; code <= 0xFFFF; ++code) {
        const std::string_view alpha2 = countryForDiallingCode(static_cast<std::uint16_t>(code));
        if (alpha2.empty())
            continue;
        const auto back = diallingCodeForCountry(alpha2);
        QVERIFY(back);
        QCOMPARE(int(*back), code);
    }
    int countries = 0;
    for (char a = 'A'; a <= 'Z'; ++a)
        for (char b = 'A'; b <= 'Z'; ++b)
            countries += diallingCodeForCountry(std::string{a, b}) ? 1 : 0;
    QCOMPARE(countries, 246);
}

// ------------------------------------------------------------------- speed

void TestTextFormat::wellEquippedFrameText()
{
    const QByteArray frame = readVector("well-equipped.bin");
    QCOMPARE(frame.size(), qsizetype(kFrameSize));
    const DecodeResult d = decodeFrame(std::span(reinterpret_cast<const std::uint8_t*>(frame.data()), kFrameSize));
    QVERIFY(d.ok());
    QCOMPARE(q(formatMessage(d.message)), QByteArray(kWellEquippedText));
}

// Input found from outside to break the error messages: every message whole,
// at its line and column, and short.
void TestTextFormat::badInput_data()
{
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QByteArray>("error");  // Diagnostic::toString() of the one error
    const QByteArray control = " in the text; the format is printable text (inside quotes write any byte as \\xHH)";
    QTest::newRow("NUL in a value") << QByteArray("eng_ID 1\0002", 10)
                                    << "line 1 column 9: control byte \\x00" + control;
    QTest::newRow("NUL in a name") << QByteArray("ID_msg 1\nID\000msg 2\n", 18)
                                   << "line 2 column 3: control byte \\x00" + control;
    QTest::newRow("escape byte") << QByteArray("system_ID \"A\x1B[2J\"")
                                 << "line 1 column 13: control byte \\x1B" + control;
    QTest::newRow("DEL") << QByteArray("ID_msg 1\x7F") << "line 1 column 9: control byte \\x7F" + control;
    QTest::newRow("carriage return inside a line")
        << QByteArray("ID_msg\r1\r\n") << "line 1 column 7: control byte \\x0D" + control;

    const QByteArray big(10 << 20, 'A');
    const QByteArray shown = QByteArray(40, 'A') + "... (10485760 bytes)";
    QTest::newRow("10 MB text value") << "system_ID " + big
                                      << "line 1 column 11: system_ID: text \"" + shown +
                                             "\" is 10485760 characters, 10485752 more than the 8 allowed";
    QTest::newRow("10 MB number") << "ID_msg " + QByteArray(10 << 20, '9')
                                  << "line 1 column 8: ID_msg: '" + QByteArray(40, '9') +
                                         "... (10485760 bytes)' does not fit in 64 bits; expected an integer from 0 to "
                                         "16777215 (decimal or 0x hex)";
    QTest::newRow("10 MB name") << big + " 1"
                                << "line 1 column 1: " + shown + ": unknown item '" + shown + "'";
    QTest::newRow("10 MB quoted value")
        << "ID_msg \"" + big + "\""
        << "line 1 column 8: ID_msg: expected an integer from 0 to 16777215 (decimal or 0x hex), got quoted text \"" +
               QByteArray(39, 'A') + "... (10485762 bytes)";
    // Bytes of 0x80 and above are written \xHH, UTF-8 or not, so that
    // whatever was typed reaches a terminal or a log as plain ASCII.
    QTest::newRow("long UTF-8 name") << QByteArray("A") + QByteArray("\xC3\xA9").repeated(30) + " 1"
                                     << "line 1 column 1: A" + QByteArray("\\xC3\\xA9").repeated(19) +
                                            "\\xC3... (61 bytes): unknown item 'A" +
                                            QByteArray("\\xC3\\xA9").repeated(19) + "\\xC3... (61 bytes)'";
    QTest::newRow("byte 0xFF in a name") << QByteArray("ID_m\xFFsg 1")
                                         << QByteArray("line 1 column 1: ID_m\\xFFsg: unknown item 'ID_m\\xFFsg'");
    QTest::newRow("byte 0x80 after a closing quote")
        << QByteArray("cam_ID \"NIK\"\x80 1")
        << QByteArray("line 1 column 13: expected a space after the closing \", got '\\x80'");
}

void TestTextFormat::badInput()
{
    QFETCH(QByteArray, text);
    QFETCH(QByteArray, error);
    const ParseResult r = parseMessage(std::string_view(text.constData(), static_cast<std::size_t>(text.size())));
    QCOMPARE(r.errors.size(), std::size_t{1});
    QCOMPARE(q(r.errors.front().toString()), error);
    QCOMPARE(r.unlistedErrors, std::size_t{0});
}

void TestTextFormat::byteOrderMarkIsSkipped()
{
    ParseResult r = parseMessage("\xEF\xBB\xBFID_msg 133\nSA_zoom_LHS_cam 35\n");
    QVERIFY2(r.ok(), dump(r.errors).c_str());
    QCOMPARE(r.message.header.number(ItemId::ID_msg), 133);
    QCOMPARE(r.message.sense.number(ItemId::SA_zoom_LHS_cam), 35);
    // Columns count from after the mark, as an editor shows them.
    r = parseMessage("\xEF\xBB\xBFID_msg x\n");
    QCOMPARE(q(dump(r.errors)),
             QByteArray("line 1 column 8: ID_msg: expected an integer from 0 to 16777215 (decimal or "
                        "0x hex), got 'x'\n"));
    // Only at the very start: elsewhere it is an unknown name as written.
    r = parseMessage("ID_msg 1\n\xEF\xBB\xBFID_msg 2\n");
    QCOMPARE(q(dump(r.errors)),
             QByteArray("line 2 column 1: \\xEF\\xBB\\xBFID_msg: unknown item '\\xEF\\xBB\\xBFID_msg'\n"));
}

void TestTextFormat::errorsAreCapped()
{
    std::string text;
    for (int i = 0; i < 1000000; ++i)
        text += "foo 1\n";
    const ParseResult r = parseMessage(text);
    QCOMPARE(r.errors.size(), kMaxListedErrors);
    QCOMPARE(r.unlistedErrors, std::size_t{1000000} - kMaxListedErrors);
    QCOMPARE(q(r.errors.front().toString()), QByteArray("line 1 column 1: foo: unknown item 'foo'"));
    QCOMPARE(r.errors.back().line, 20);
}

void TestTextFormat::block1OverflowNamesTheItem()
{
    // Nine radios of 23 bytes (207) fit; the tenth stops at its Tx_freq (224).
    std::string text;
    for (int i = 0; i < 10; ++i)
        text += "system_ID R" + std::to_string(i) +
                "\nRx_freq 1\nTx_freq 1\nTx_OP_power 1\nreceiver_control receiver=ON transmitter=ON\n";
    ParseResult r = parseMessage(text);
    QCOMPARE(q(dump(r.errors)), QByteArray("line 48 column 1: Tx_freq: BLOCK 1 is full here: the items need 230 bytes, "
                                           "7 more than the 223 a block holds\n"));
    QCOMPARE(r.errors.front().kind, Diagnostic::Kind::DoesNotFit);
    // The same text under the secure link's limits, with ID_msg, time_UTC and
    // date_UTC to be filled in (12 bytes): 195 bytes left, full in the ninth radio.
    constexpr std::array<ItemId, 3> filled{ItemId::ID_msg, ItemId::time_UTC, ItemId::date_UTC};
    r = parseMessage(text, EncodeOptions{16, 199}, filled);
    QCOMPARE(q(dump(r.errors)),
             QByteArray("line 42 column 1: Rx_freq: BLOCK 1 is full here: the items need 242 bytes plus 16 bytes of "
                        "required padding, 35 more than the 223 a block holds (counting ID_msg, time_UTC and "
                        "date_UTC, filled in when not given)\n"));
    // Text that fits gets no error, and encodes.
    text.resize(text.find("system_ID R9"));
    r = parseMessage(text);
    QVERIFY(r.ok());
    Diagnostics errors;
    QVERIFY(encodeFrame(r.message, errors));
}

QTEST_APPLESS_MAIN(TestTextFormat)
#include "tst_textformat.moc"
