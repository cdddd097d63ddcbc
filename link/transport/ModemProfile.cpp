#include "link/transport/ModemProfile.h"

#include "link/common/NameTable.h"

#include <algorithm>

namespace modem {

namespace {

// Iridium's ISU AT command set is the same on the 9522B and 9523
// transceivers and the 9555 and 9575 handsets (through their data cable):
// RTS/CTS with &K3, the 9,600 bit/s V.110 bearer (+CBST=71,0,1, which
// carries data better than the default V.32 one), the indicator events of
// +CIER (+CIEV:0,<signal 0..5>, +CIEV:1,<service 0/1>) and a +CSQ in bars.
Profile iridium(const QString& name, const QString& title, const QString& note)
{
    return Profile{name,
                   title,
                   note,
                   {"AT&K3", "AT+CBST=71,0,1"},
                   "AT+CIER=1,1,1",
                   "AT+CREG?",
                   "AT+CSQ",
                   SignalScale::Bars};
}

// A phone of the GSM family (3GPP TS 27.007): unsolicited +CREG: <stat>
// after AT+CREG=1, and +CSQ: <rssi>,<ber> with rssi 0..31.
Profile gsmFamily(const QString& name, const QString& title, const QString& note, QList<QByteArray> setup)
{
    return Profile{name, title, note, std::move(setup), "AT+CREG=1", "AT+CREG?", "AT+CSQ", SignalScale::Rssi27007};
}

constexpr auto kRegistrationTexts = std::to_array<Named<Registration>>({
    {.value = Registration::Unknown, .name = "registration not known"},
    {.value = Registration::NotSearching, .name = "not registered, not searching"},
    {.value = Registration::Home, .name = "registered"},
    {.value = Registration::Searching, .name = "not registered, searching for the network"},
    {.value = Registration::Denied, .name = "registration denied"},
    {.value = Registration::StatUnknown, .name = "registration unknown to the phone"},
    {.value = Registration::Roaming, .name = "registered, roaming"},
});

QList<Profile> makeProfiles()
{
    return {
        gsmFamily(QStringLiteral("generic"), QStringLiteral("Generic (3GPP TS 27.007)"),
                  QStringLiteral("Any phone that answers AT+CREG? and AT+CSQ; add its bearer (AT+CBST) to the init "
                                 "string"),
                  {}),
        iridium(QStringLiteral("iridium-9522b"), QStringLiteral("Iridium 9522B"),
                QStringLiteral("Iridium 9522B L-band transceiver: V.110 bearer at 9,600 bit/s, service and signal "
                               "from +CIEV")),
        iridium(QStringLiteral("iridium-9523"), QStringLiteral("Iridium 9523"),
                QStringLiteral("Iridium 9523 core transceiver: as the 9522B")),
        iridium(QStringLiteral("iridium-9555"), QStringLiteral("Iridium 9555"),
                QStringLiteral("Iridium 9555 handset through its data cable: as the 9522B")),
        iridium(QStringLiteral("iridium-9575"), QStringLiteral("Iridium 9575 Extreme"),
                QStringLiteral("Iridium 9575 Extreme handset through its data cable: as the 9522B")),
        gsmFamily(QStringLiteral("isatphone"), QStringLiteral("Inmarsat IsatPhone"),
                  QStringLiteral("Inmarsat IsatPhone Pro and IsatPhone 2 through their data port: circuit-switched "
                                 "data, 9,600 bit/s non-transparent bearer"),
                  {"AT&K3", "AT+CBST=7,0,1"}),
        gsmFamily(QStringLiteral("bgan"), QStringLiteral("Inmarsat BGAN"),
                  QStringLiteral("Inmarsat BGAN terminal (Explorer, Hughes 9201/9202) on its AT port: the "
                                 "circuit-switched 64 kbit/s UDI bearer, which carries the 9,600 bit/s line"),
                  {"AT&K3", "AT+CBST=134,1,0"}),
        gsmFamily(QStringLiteral("thuraya"), QStringLiteral("Thuraya"),
                  QStringLiteral("Thuraya XT, XT-LITE data port, SO-2510 or FDU: circuit-switched data, 9,600 "
                                 "bit/s non-transparent bearer"),
                  {"AT&K3", "AT+CBST=7,0,1"}),
        Profile{QStringLiteral("hayes"),
                QStringLiteral("Modem without a network"),
                QStringLiteral("A telephone-line or cable modem: no registration or signal to read; dialled at once"),
                {},
                {},
                {},
                {},
                SignalScale::Rssi27007},
    };
}

// The numbers of an information response's value, those outside quotes;
// a field that is not a whole number (a hexadecimal location) is skipped.
QList<int> numbersOf(QByteArrayView value)
{
    QList<int> numbers;
    bool quoted = false;
    QByteArray field;
    const auto take = [&] {
        const QByteArray trimmed = field.trimmed();
        bool ok = false;
        const int n = trimmed.toInt(&ok);
        if (ok && !trimmed.isEmpty())
            numbers << n;
        field.clear();
    };
    for (const char c : value) {
        if (c == '"') {
            quoted = !quoted;
            field.clear();
            continue;
        }
        if (quoted)
            continue;
        if (c == ',')
            take();
        else
            field += c;
    }
    take();
    return numbers;
}

}  // namespace

const QList<Profile>& profiles()
{
    static const QList<Profile> kProfiles = makeProfiles();
    return kProfiles;
}

const Profile& defaultProfile()
{
    return profiles().front();
}

std::optional<Profile> findProfile(const QString& name)
{
    for (const Profile& p : profiles())
        if (p.name.compare(name.trimmed(), Qt::CaseInsensitive) == 0)
            return p;
    return std::nullopt;
}

QStringList profileNames()
{
    QStringList names;
    for (const Profile& p : profiles())
        names << p.name;
    return names;
}

bool isRegistered(Registration r)
{
    return r == Registration::Home || r == Registration::Roaming;
}

QString registrationText(Registration r)
{
    return nameText(kRegistrationTexts, r);
}

bool Service::canDial() const
{
    // Iridium's service indicator speaks for the network even without a +CREG.
    const bool registered = isRegistered(registration) ||
                            (registration == Registration::Unknown && available.value_or(false));
    return registered && bars != 0 && available.value_or(true);
}

QString Service::text() const
{
    QString where = registrationText(registration);
    if (registration == Registration::Unknown && available)
        where = *available ? QStringLiteral("network service available") : QStringLiteral("no network service");
    else if (available && !*available && isRegistered(registration))
        where += QStringLiteral(", no network service");
    const QString signal = bars < 0    ? QStringLiteral("signal not known")
                           : bars == 0 ? QStringLiteral("no signal")
                                       : QStringLiteral("signal %1 of 5").arg(bars);
    return QStringLiteral("%1, %2").arg(where, signal);
}

int barsFromSignal(int rssi, SignalScale scale)
{
    if (scale == SignalScale::Bars)
        return rssi >= 0 && rssi <= 5 ? rssi : -1;
    // 27.007: 0 is -113 dBm or less, 31 is -51 dBm or more, 2 dBm a step.
    if (rssi < 0 || rssi > 31)
        return -1;
    if (rssi == 0)
        return 0;
    return std::min(5, 1 + (rssi - 1) / 6);  // 1-6: 1 bar ... 25-30: 5, 31: 5
}

int signalFromBars(int bars, SignalScale scale)
{
    if (scale == SignalScale::Bars)
        return std::clamp(bars, 0, 5);
    if (bars <= 0)
        return 0;
    return std::min(31, 1 + (std::min(bars, 5) - 1) * 6 + 3);  // the middle of the bar's range
}

bool parseServiceLine(QByteArrayView line, SignalScale scale, Service& service)
{
    QByteArray text = line.toByteArray().trimmed().toUpper();
    const qsizetype colon = text.indexOf(':');
    if (!text.startsWith('+') || colon < 0)
        return false;
    QByteArray name = text.left(colon);
    name.replace(' ', QByteArray());
    const QList<int> numbers = numbersOf(QByteArrayView(text).sliced(colon + 1));
    if (name == "+CREG" || name == "+CGREG" || name == "+CEREG") {
        if (numbers.isEmpty())
            return false;
        const int stat = numbers.size() == 1 ? numbers[0] : numbers[1];
        if (stat < 0 || stat > 5)
            return false;
        service.registration = Registration(stat);
        return true;
    }
    if (name == "+CSQ" || name == "+CSQF") {
        if (numbers.isEmpty())
            return false;
        service.bars = barsFromSignal(numbers[0], scale);
        return true;
    }
    if (name == "+CIEV") {
        if (numbers.size() < 2)
            return false;
        if (numbers[0] == 0) {
            service.bars = barsFromSignal(numbers[1], SignalScale::Bars);
            return true;
        }
        if (numbers[0] == 1) {
            service.available = numbers[1] != 0;
            return true;
        }
        return false;  // the antenna and others: nothing the console uses
    }
    return false;
}

}  // namespace modem
