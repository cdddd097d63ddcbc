#include "link/session/LinkSettings.h"

#include "link/transport/ModemLink.h"
#include "link/transport/SerialLink.h"
#include "link/transport/UdpLink.h"

#include <QHostAddress>
#include <QLocale>
#include <QSettings>

#include <variant>

namespace {

// The settings kept under "link/", each under its member's name: save() and
// load() both go through this one list. The transport, kept as a word, is
// apart; the key file's path is kept, the key stays in its file.
using Member = std::variant<QString LinkSettings::*, qint32 LinkSettings::*, quint16 LinkSettings::*,
                            bool LinkSettings::*, double LinkSettings::*>;
struct Stored {
    const char* key;
    Member member;
};
using L = LinkSettings;
const Stored kStored[] = {
    {"serialPort", &L::serialPort},
    {"baudRate", &L::baudRate},
    {"localAddress", &L::localAddress},
    {"localPort", &L::localPort},
    {"remoteAddress", &L::remoteAddress},
    {"remotePort", &L::remotePort},
    {"keyPath", &L::keyPath},
    {"dialNumber", &L::dialNumber},
    {"modemInit", &L::modemInit},
    {"modemProfile", &L::modemProfile},
    {"callCurrency", &L::callCurrency},
    {"rtsCts", &L::rtsCts},
    {"callCostPerMinute", &L::callCostPerMinute},
    {"satelliteDelayMs", &L::satelliteDelayMs},
};

// A stored value read back as its member's type.
void assign(QString& to, const QVariant& v)
{
    to = v.toString();
}
void assign(qint32& to, const QVariant& v)
{
    to = v.toInt();
}
void assign(quint16& to, const QVariant& v)
{
    to = quint16(v.toUInt());
}
void assign(bool& to, const QVariant& v)
{
    to = v.toBool();
}
void assign(double& to, const QVariant& v)
{
    to = v.toDouble();
}

}  // namespace

QString LinkSettings::defaultCurrency()
{
    // The C locale knows none: a satellite call is billed in US dollars most often.
    const QString code = QLocale::system().currencySymbol(QLocale::CurrencyIsoCode);
    return code.isEmpty() ? QStringLiteral("USD") : code;
}

bool LinkSettings::setModemProfile(const QString& name, QString* error)
{
    const std::optional<modem::Profile> profile = modem::findProfile(name);
    if (profile)
        modemProfile = profile->name;
    else if (error)
        *error = QObject::tr("no modem profile is called \"%1\"; there are %2")
                     .arg(name, modem::profileNames().join(QStringLiteral(", ")));
    return profile.has_value();
}

std::unique_ptr<Link> LinkSettings::createLink(QString* error, std::shared_ptr<Clock> clock) const
{
    const auto fail = [&](const QString& why) -> std::unique_ptr<Link> {
        if (error)
            *error = why;
        return nullptr;
    };
    if (transport == Transport::Serial) {
        if (serialPort.trimmed().isEmpty())
            return fail(QObject::tr("Choose a serial port"));
        if (baudRate <= 0)
            return fail(QObject::tr("The bit rate must be positive"));
        if (!dialsModem())
            return std::make_unique<SerialLink>(serialPort.trimmed(), baudRate, nullptr, clock);
        if (!modemInit.trimmed().toUpper().startsWith(QLatin1String("AT")))
            return fail(QObject::tr("The modem's init string must start with AT: \"%1\"").arg(modemInit));
        const std::optional<modem::Profile> profile = modem::findProfile(modemProfile);
        if (!profile)
            return fail(QObject::tr("No modem profile is called \"%1\"; there are %2")
                            .arg(modemProfile, modem::profileNames().join(QStringLiteral(", "))));
        auto port = std::make_unique<SerialLink>(serialPort.trimmed(), baudRate,
                                                 rtsCts ? SerialLink::FlowControl::RtsCts : SerialLink::FlowControl::None,
                                                 nullptr, clock);
        ModemLink::Options modem;
        modem.number = dialNumber.trimmed();
        modem.initString = modemInit.trimmed().toLatin1();
        modem.profile = *profile;
        modem.costPerMinute = callCostPerMinute;
        modem.costCurrency = callCurrency.trimmed();
        modem.clock = std::move(clock);
        return std::make_unique<ModemLink>(std::move(port), modem);
    }
    const QHostAddress local(localAddress.trimmed());
    const QHostAddress remote(remoteAddress.trimmed());
    if (local.isNull())
        return fail(QObject::tr("\"%1\" is not a local IP address").arg(localAddress));
    if (remote.isNull())
        return fail(QObject::tr("\"%1\" is not an IP address").arg(remoteAddress));
    if (remotePort == 0)
        return fail(QObject::tr("Give the aircraft's UDP port"));
    return std::make_unique<UdpLink>(local, localPort, remote, remotePort);
}

QString LinkSettings::summary() const
{
    QString where = transport == Transport::Serial ? QObject::tr("serial %1 at %2 bit/s").arg(serialPort).arg(baudRate)
                                                   : QObject::tr("UDP %1:%2").arg(remoteAddress).arg(remotePort);
    if (dialsModem()) {
        const std::optional<modem::Profile> profile = modem::findProfile(modemProfile);
        // The number, not "dialling": the summary stays the link's name in
        // the title for the whole call.
        where = QObject::tr("%1, phone %2 (%3)")
                    .arg(where, dialNumber.trimmed(), profile ? profile->title : modemProfile);
    }
    return keyPath.isEmpty() ? where : QObject::tr("%1, encrypted").arg(where);
}

std::optional<LinkSettings> LinkSettings::udpRemote(const QString& hostAndPort, QString* error)
{
    const qsizetype colon = hostAndPort.lastIndexOf(QLatin1Char(':'));
    bool ok = false;
    const uint port = colon > 0 ? hostAndPort.mid(colon + 1).toUInt(&ok) : 0;
    const QString host = hostAndPort.left(colon);
    if (!ok || port == 0 || port > 65535 || QHostAddress(host).isNull()) {
        if (error)
            *error = QObject::tr("\"%1\" is not HOST:PORT with an IP address and a port 1..65535").arg(hostAndPort);
        return std::nullopt;
    }
    LinkSettings s;
    s.transport = Transport::Udp;
    s.remoteAddress = host;
    s.remotePort = quint16(port);
    return s;
}

std::optional<LinkSettings> LinkSettings::serial(const QString& port, const QString& baudRate, QString* error)
{
    LinkSettings s;
    bool ok = false;
    s.transport = Transport::Serial;
    s.serialPort = port;
    s.baudRate = baudRate.toInt(&ok);
    if (ok && s.baudRate > 0)
        return s;
    if (error)
        *error = QObject::tr("\"%1\" is not a bit rate").arg(baudRate);
    return std::nullopt;
}

void LinkSettings::save(QSettings& settings) const
{
    settings.beginGroup(QStringLiteral("link"));
    settings.setValue(QStringLiteral("transport"),
                      transport == Transport::Serial ? QStringLiteral("serial") : QStringLiteral("udp"));
    for (const Stored& stored : kStored)
        std::visit([&](auto member) { settings.setValue(QLatin1String(stored.key), this->*member); }, stored.member);
    settings.endGroup();
}

LinkSettings LinkSettings::load(const QSettings& settings)
{
    const LinkSettings defaults;
    const auto value = [&](const char* key, const QVariant& fallback) {
        return settings.value(QStringLiteral("link/") + QLatin1String(key), fallback);
    };
    LinkSettings s;
    s.transport =
        value("transport", QString()).toString() == QLatin1String("serial") ? Transport::Serial : Transport::Udp;
    for (const Stored& stored : kStored)
        std::visit([&](auto member) { assign(s.*member, value(stored.key, defaults.*member)); }, stored.member);
    return s;
}
