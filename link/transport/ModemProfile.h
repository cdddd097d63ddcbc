#pragma once

// The satellite phones operators use as data modems, each with its own set-up
// (docs/modem.md, "Profiles"): what goes after the init string (the data
// bearer, AT+CBST, and its kin), how the phone tells that it is registered
// with the network (AT+CREG?, Iridium's +CIEV indications) and how strong
// the signal is (AT+CSQ, on a scale of its own). One table, read by the
// console's modem control (ModemLink), the link pane, gcs --modem-profile
// and the satellite modem model, which speaks each profile's dialect.
//
// Also the parsing of what phones say about their service. Liberal: spaces
// anywhere, either case, "+CREG: n,stat" (the answer to AT+CREG?) and
// "+CREG: stat" (unsolicited, after AT+CREG=1), with or without location
// fields, "+CSQ: rssi,ber" and Iridium's "+CSQ:rssi", "+CIEV: 0,n" (signal)
// and "+CIEV: 1,n" (service).

#include <QByteArray>
#include <QByteArrayView>
#include <QList>
#include <QString>
#include <QStringList>

#include <optional>

namespace modem {

// How a phone's AT+CSQ counts.
enum class SignalScale {
    Bars,      // 0..5: Iridium, what the handset's display shows
    Rssi27007  // 0..31 (-113 dBm .. -51 dBm and up) and 99 "not known": 3GPP TS 27.007
};

struct Profile {
    QString name;   // for --modem-profile and the settings: "iridium-9522b"
    QString title;  // for people: "Iridium 9522B"
    QString note;   // what it is, for the link pane's tool tip
    // Sent one at a time after the init string; each must be answered OK.
    QList<QByteArray> setup;
    // Turns the phone's own reports of registration and signal on; ERROR
    // is tolerated (the console then asks every few seconds).
    QByteArray indications;
    // Empty for a modem with no network (a cable, a telephone line): it is
    // dialled without asking.
    QByteArray registrationQuery;
    QByteArray signalQuery;
    SignalScale scale = SignalScale::Rssi27007;

    bool hasNetwork() const { return !registrationQuery.isEmpty(); }
};

// Every profile, the default first.
const QList<Profile>& profiles();
const Profile& defaultProfile();
// Nothing for a name no profile has (any case).
std::optional<Profile> findProfile(const QString& name);
QStringList profileNames();

// 3GPP TS 27.007's <stat> of +CREG.
enum class Registration {
    Unknown = -1,      // not asked yet, or the phone did not say
    NotSearching = 0,  // not registered, not looking for a network
    Home = 1,
    Searching = 2,
    Denied = 3,
    StatUnknown = 4,  // the phone itself does not know
    Roaming = 5,
};
bool isRegistered(Registration r);
QString registrationText(Registration r);  // "registered", "searching for the network", ...

// What the phone said about its service, kept as it comes.
struct Service {
    Registration registration = Registration::Unknown;
    int bars = -1;            // 0..5; -1: not known
    std::optional<bool> available;  // Iridium's +CIEV:1 service indicator

    // Registered, and the signal not known to be nil.
    bool canDial() const;
    // "registered, signal 3 of 5", "not registered (searching for the network), no signal"
    QString text() const;
    friend bool operator==(const Service&, const Service&) = default;
};

// 0..5 bars from a +CSQ <rssi> on `scale`; -1 for "not known" (99).
int barsFromSignal(int rssi, SignalScale scale);
// The +CSQ <rssi> a phone on `scale` reports for `bars` (the model's side).
int signalFromBars(int bars, SignalScale scale);

// One line a phone sent, without its CR LF. In +CREG the numbers that are
// not in quotes count: one is the unsolicited <stat>, two or more are the
// answer's <n>,<stat> (location fields, quoted or hexadecimal, are left
// out). True when the line was about the service (`service` updated);
// false for anything else, a result code or a line that does not parse.
bool parseServiceLine(QByteArrayView line, SignalScale scale, Service& service);

}  // namespace modem
