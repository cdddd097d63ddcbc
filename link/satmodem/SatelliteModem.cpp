#include "link/satmodem/SatelliteModem.h"

#include "link/satmodem/PseudoTerminal.h"

#include <QSocketNotifier>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstring>
#include <deque>
#include <utility>

#include <fcntl.h>
#include <pty.h>
#include <sys/inotify.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

using modem::ResultCode;

namespace {

constexpr int kPaceIntervalMs = 20;
constexpr int kGuardUnitMs = 20;              // S12 counts fiftieths of a second
constexpr qsizetype kCommandLineLimit = 256;  // a modem's line buffer; a longer line is an ERROR
constexpr qsizetype kReadChunk = 4096;
constexpr char kBackspace = 8;
constexpr char kDelete = 127;

constexpr std::size_t kAutoAnswerRings = 0;  // S0
constexpr std::size_t kGuardTime = 12;       // S12

using Registers = std::array<int, 256>;

// As at power on, ATZ and AT&F: the values Hayes modems start with, though
// only S0 and S12 change what this model does.
Registers defaultRegisters()
{
    Registers r{};
    r[2] = '+';   // escape character
    r[3] = '\r';  // line end
    r[4] = '\n';  // result line feed
    r[5] = kBackspace;
    r[6] = 2;   // seconds to wait for a dial tone
    r[7] = 50;  // seconds to wait for carrier
    r[8] = 2;   // comma pause
    r[10] = 14;
    r[kGuardTime] = 50;
    return r;
}

QString systemError(const QString& what)
{
    return QStringLiteral("%1: %2").arg(what, QString::fromLocal8Bit(std::strerror(errno)));
}

char upper(char c)
{
    return c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
}

bool isDigit(char c)
{
    return c >= '0' && c <= '9';
}

// The decimal number at `at`, moved past; `otherwise` when none is there.
// Capped, so that a long run of digits cannot overflow.
int numberAt(QByteArrayView text, qsizetype& at, int otherwise)
{
    if (at >= text.size() || !isDigit(text[at]))
        return otherwise;
    int value = 0;
    for (; at < text.size() && isDigit(text[at]); ++at)
        value = std::min(value * 10 + (text[at] - '0'), 1'000'000);
    return value;
}

// What follows ATD, less the tone or pulse choice and any spaces.
QByteArray numberDialled(QByteArrayView dialString)
{
    QByteArray number = dialString.toByteArray().replace(' ', QByteArray());
    if (!number.isEmpty() && (upper(number[0]) == 'T' || upper(number[0]) == 'P'))
        number.remove(0, 1);
    return number;
}

}  // namespace

// The pty (master, slave and device): its slave held, so the master never
// reads "no one there" (EIO) while no program has it.
struct SatelliteModem::Port : PseudoTerminal {
    enum class Mode { Command, Dialling, Data, OnlineCommand };
    struct InFlight {
        qint64 arrivesAt = 0;
        QByteArray bytes;
    };

    int side = 0;

    // The pty.
    int watch = -1;  // of the slave's opens and closes
    std::unique_ptr<QSocketNotifier> readable;
    std::unique_ptr<QSocketNotifier> writable;
    int users = 0;       // opens of the slave by programs; the model's own is not counted
    QByteArray toUser;   // what the pty had no room for yet

    // The modem.
    Mode mode = Mode::Command;
    bool echo = true;
    Registers registers = defaultRegisters();
    QByteArray commandLine;
    bool lineTooLong = false;
    bool lineFeedMayFollow = false;  // a CR ended a line: a LF next is its partner, not input
    QByteArray dialled;
    // The network's reports: +CREG=n (0 off, 1 <stat>, 2 <stat> and location),
    // +CIER=mode,signal,service; what is held for the return to command mode.
    int registrationReports = 0;
    bool indicatorEvents = false;
    bool signalEvents = false;
    bool serviceEvents = false;
    bool heldRegistration = false;
    bool heldSignal = false;
    QByteArray bearer = "7,0,1";  // +CBST as last set
    bool dtrHangsUp = true;       // &D2 (or &D1); &D0: a program going away leaves the call up

    // The "+++" escape: pluses held back until the guard time says what they are.
    int heldPluses = 0;
    qint64 lastByteAt = 0;
    ClockTimer* guard = nullptr;  // a child of the model, so that it follows the model to another thread

    // The air, from this side.
    QByteArray waiting;  // read, not yet on the air
    std::deque<InFlight> inFlight;
    double credit = 0;   // bytes the air may still take in this tick
    bool ctsDropped = false;
};

SatelliteModem::SatelliteModem(Options options, QObject* parent)
    : QObject(parent),
      m_options(options),
      m_clock(options.clock ? options.clock : std::make_shared<SystemClock>()),
      m_openedSteadyMicros(m_clock->steadyMicros()),
      m_setupTimer(m_clock->createTimer(this)),
      m_ringTimer(m_clock->createTimer(this)),
      m_dropTimer(m_clock->createTimer(this)),
      m_paceTimer(m_clock->createTimer(this, Qt::PreciseTimer)),
      m_serviceTimer(m_clock->createTimer(this)),
      m_random(options.seed)
{
    m_bars = m_options.noService ? 0 : 4;
    connect(m_serviceTimer, &ClockTimer::timeout, this, &SatelliteModem::applyService);
    for (int side = 0; side < 2; ++side) {
        m_ports[std::size_t(side)] = std::make_unique<Port>();
        Port& p = port(side);
        p.side = side;
        // Precise: a coarse timer may fire early, inside the guard time.
        p.guard = m_clock->createTimer(this, Qt::PreciseTimer);
        connect(p.guard, &ClockTimer::timeout, this, [this, &p] { onGuardTimeAfterEscape(p); });
    }
    connect(m_setupTimer, &ClockTimer::timeout, this, &SatelliteModem::onSetupTimeOver);
    // Rings and the pace go on until stopped.
    connect(m_ringTimer, &ClockTimer::timeout, this, [this] {
        m_ringTimer->start(m_options.ringInterval);
        ring();
    });
    connect(m_dropTimer, &ClockTimer::timeout, this, &SatelliteModem::dropCall);
    connect(m_paceTimer, &ClockTimer::timeout, this, [this] {
        m_paceTimer->start(std::chrono::milliseconds(kPaceIntervalMs));
        pace();
    });
}

SatelliteModem::~SatelliteModem()
{
    m_inotifyNotifier.reset();
    for (auto& p : m_ports) {
        p->readable.reset();
        p->writable.reset();
        if (p->master >= 0)
            ::close(p->master);
        if (p->slave >= 0)
            ::close(p->slave);
    }
    if (m_inotify >= 0)
        ::close(m_inotify);
}

bool SatelliteModem::open(QString* error)
{
    m_inotify = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (m_inotify < 0) {
        if (error)
            *error = systemError(QStringLiteral("cannot watch the pseudo-terminals"));
        return false;
    }
    for (int side = 0; side < 2; ++side) {
        if (!openPort(side, error))
            return false;
    }
    m_inotifyNotifier = std::make_unique<QSocketNotifier>(m_inotify, QSocketNotifier::Read, this);
    connect(m_inotifyNotifier.get(), &QSocketNotifier::activated, this, &SatelliteModem::readUserOpensAndCloses);
    m_openedSteadyMicros = m_clock->steadyMicros();  // the service script's time starts now
    applyService();
    return true;
}

std::optional<std::vector<SatelliteModem::Options::ServiceStep>> SatelliteModem::parseService(const QString& text,
                                                                                              QString* error)
{
    std::vector<Options::ServiceStep> steps;
    for (const QString& item : text.split(QLatin1Char(','), Qt::SkipEmptyParts)) {
        const QStringList parts = item.split(QLatin1Char(':'));
        bool timeOk = false, barsOk = false;
        const double at = parts.value(0).trimmed().toDouble(&timeOk);
        const int bars = parts.value(1).trimmed().toInt(&barsOk);
        if (parts.size() != 2 || !timeOk || !barsOk || at < 0 || bars < 0 || bars > 5 ||
            (!steps.empty() && at * 1000 < double(steps.back().at.count()))) {
            if (error)
                *error = QStringLiteral("\"%1\" in \"%2\" is not SECONDS:BARS (bars 0 to 5, seconds in order), as "
                                        "in 0:0,10:4,60:1")
                             .arg(item, text);
            return std::nullopt;
        }
        steps.push_back({std::chrono::milliseconds(qint64(at * 1000)), bars});
    }
    return steps;
}

// The script's steps that are due, then a timer for the next one.
void SatelliteModem::applyService()
{
    int bars = m_bars;
    const auto& script = m_options.service;
    while (m_serviceStep < script.size() && script[m_serviceStep].at.count() <= now())
        bars = m_options.noService ? 0 : script[m_serviceStep++].bars;
    if (m_serviceStep < script.size())
        m_serviceTimer->start(std::chrono::milliseconds(std::max<qint64>(0, script[m_serviceStep].at.count() - now())));
    setSignalBars(bars);
}

void SatelliteModem::setSignalBars(int bars)
{
    bars = std::clamp(bars, 0, 5);
    if (bars == m_bars)
        return;
    const bool registrationChanged = (bars > 0) != (m_bars > 0);
    m_bars = bars;
    emit signalChanged(bars);
    for (auto& p : m_ports)
        report(*p, registrationChanged, true);
    if (bars == 0 && m_call.state != CallState::Idle)
        dropCall();  // the network lost the phones
}

void SatelliteModem::report(Port& p, bool registrationChanged, bool signalChanged)
{
    if (p.mode == Port::Mode::Data || p.mode == Port::Mode::Dialling) {
        p.heldRegistration = p.heldRegistration || registrationChanged;
        p.heldSignal = p.heldSignal || signalChanged;
        return;
    }
    const int stat = registered() ? 1 : 2;
    if (registrationChanged && p.registrationReports > 0)
        sendInformation(p, "+CREG: " + QByteArray::number(stat));
    if (p.indicatorEvents && signalChanged && p.signalEvents)
        sendInformation(p, "+CIEV:0," + QByteArray::number(m_bars));
    if (p.indicatorEvents && registrationChanged && p.serviceEvents)
        sendInformation(p, "+CIEV:1," + QByteArray::number(registered() ? 1 : 0));
}

void SatelliteModem::flushReports(Port& p)
{
    const bool registration = std::exchange(p.heldRegistration, false);
    const bool signal = std::exchange(p.heldSignal, false);
    if (registration || signal)
        report(p, registration, signal);
}

bool SatelliteModem::openPort(int side, QString* error)
{
    Port& p = port(side);
    if (!openRawPseudoTerminal(p, error))
        return false;
    // Holding the slave hides a program's going away from the master, so its
    // opens and closes are counted instead.
    p.watch = ::inotify_add_watch(m_inotify, p.device.toLocal8Bit().constData(), IN_OPEN | IN_CLOSE);
    if (p.watch < 0) {
        if (error)
            *error = systemError(QStringLiteral("cannot watch %1").arg(p.device));
        return false;
    }
    p.readable = std::make_unique<QSocketNotifier>(p.master, QSocketNotifier::Read, this);
    connect(p.readable.get(), &QSocketNotifier::activated, this, [this, &p] { readPty(p); });
    p.writable = std::make_unique<QSocketNotifier>(p.master, QSocketNotifier::Write, this);
    p.writable->setEnabled(false);
    connect(p.writable.get(), &QSocketNotifier::activated, this, [this, &p] { flushToUser(p); });
    return true;
}

QString SatelliteModem::device(int side) const
{
    return m_ports[std::size_t(side)]->device;
}

QByteArray SatelliteModem::dialledNumber(int side) const
{
    return m_ports[std::size_t(side)]->dialled;
}

int SatelliteModem::sideOf(const Port& p) const
{
    return p.side;
}

// ---------------------------------------------------------------------------
// The ptys and who has them open.

void SatelliteModem::readUserOpensAndCloses()
{
    alignas(inotify_event) char buffer[4096];
    for (ssize_t n; (n = ::read(m_inotify, buffer, sizeof buffer)) > 0;) {
        for (const char* at = buffer; at < buffer + n;) {
            const auto* event = reinterpret_cast<const inotify_event*>(at);
            at += sizeof(inotify_event) + event->len;
            for (auto& p : m_ports) {
                if (event->wd != p->watch)
                    continue;
                if (event->mask & IN_OPEN)
                    ++p->users;
                else if ((event->mask & IN_CLOSE) && p->users > 0 && --p->users == 0)
                    forgetUser(*p);
            }
        }
    }
}

// The line is left as a new program should find it, at once; what the call
// makes of it waits for the event loop, as this may be found in the middle
// of anything.
void SatelliteModem::forgetUser(Port& p)
{
    p.toUser.clear();
    p.writable->setEnabled(false);
    // What it left unread must not greet the next program, nor what it wrote
    // before going reach the far side: DTR dropped.
    ::tcflush(p.slave, TCIOFLUSH);
    char discard[kReadChunk];
    while (::read(p.master, discard, sizeof discard) > 0) {
    }
    // It may have changed the line's settings or opened it exclusively (QSerialPort does).
    termios raw{};
    ::cfmakeraw(&raw);
    ::tcsetattr(p.slave, TCSANOW, &raw);
    ::ioctl(p.slave, TIOCNXCL);
    QMetaObject::invokeMethod(this, [this, side = p.side] { onUserGone(side); }, Qt::QueuedConnection);
}

// DTR dropped, as with AT&D2: the call is hung up and the modem waits in
// command mode, its settings kept. A ringing call rings on, unanswered.
void SatelliteModem::onUserGone(int side)
{
    Port& p = port(side);
    if (inCall(p) && p.dtrHangsUp)
        hangUp(p, QStringLiteral("slave closed"));
    p.commandLine.clear();
    p.lineTooLong = false;
    p.lineFeedMayFollow = false;
    emit userGone(side);
}

void SatelliteModem::readPty(Port& p)
{
    readUserOpensAndCloses();  // a program's open is known before its first bytes are
    char buffer[kReadChunk];
    while (!p.ctsDropped) {
        // In data mode no more than the buffer has room for: the rest waits
        // in the pty, as it would in the program's serial port.
        const qsizetype room = p.mode == Port::Mode::Data ? std::min(kReadChunk, bufferLimit() - p.waiting.size()) : kReadChunk;
        if (room <= 0)
            break;
        const ssize_t n = ::read(p.master, buffer, std::size_t(room));
        if (n <= 0)
            break;
        takeInput(p, QByteArrayView(buffer, n));
    }
}

void SatelliteModem::takeInput(Port& p, QByteArrayView bytes)
{
    for (qsizetype i = 0; i < bytes.size(); ++i) {
        const char c = bytes[i];
        if (std::exchange(p.lineFeedMayFollow, false) && c == '\n')
            continue;
        switch (p.mode) {
        case Port::Mode::Data:
            takeData(p, bytes.sliced(i));
            return;
        case Port::Mode::Dialling:
            if (c != '\n')
                abortDial(p);
            break;
        case Port::Mode::Command:
        case Port::Mode::OnlineCommand:
            takeCommandByte(p, c);
            break;
        }
    }
}

void SatelliteModem::send(Port& p, const QByteArray& bytes)
{
    readUserOpensAndCloses();
    if (p.users == 0)
        return;  // said to a line no program holds: lost, as on a serial port
    p.toUser += bytes;
    flushToUser(p);
}

void SatelliteModem::sendResult(Port& p, ResultCode code)
{
    const modem::Result result{code, code == ResultCode::Connect ? m_options.connectRate : 0};
    send(p, modem::resultLine(result));
    emit resultSent(p.side, result);
}

void SatelliteModem::flushToUser(Port& p)
{
    while (!p.toUser.isEmpty()) {
        const ssize_t n = ::write(p.master, p.toUser.constData(), std::size_t(p.toUser.size()));
        if (n > 0)
            p.toUser.remove(0, n);
        else if (n < 0 && errno == EINTR)
            continue;
        else if (n < 0 && errno == EAGAIN)
            break;  // the program is not reading: wait for room
        else
            p.toUser.clear();
    }
    p.writable->setEnabled(!p.toUser.isEmpty());
}

// ---------------------------------------------------------------------------
// Command mode.

void SatelliteModem::takeCommandByte(Port& p, char c)
{
    if (c == '\n')
        return;  // a line ends with CR; a LF on its own is noise
    if (p.echo)
        send(p, QByteArray(1, c));
    if (c == '\r') {
        p.lineFeedMayFollow = true;
        const bool tooLong = std::exchange(p.lineTooLong, false);
        runCommandLine(p, std::exchange(p.commandLine, {}), tooLong);
    } else if (c == kBackspace || c == kDelete) {
        p.commandLine.chop(1);
    } else if (p.commandLine.size() < kCommandLineLimit) {
        p.commandLine += c;
    } else {
        p.lineTooLong = true;
    }
}

void SatelliteModem::runCommandLine(Port& p, const QByteArray& line, bool tooLong)
{
    // A modem waits for "AT": whatever comes before it, or a line without it, is ignored.
    const qsizetype start = line.toUpper().indexOf("AT");
    if (start < 0)
        return;
    const QByteArray command = line.mid(start).trimmed();
    emit commandReceived(p.side, command);
    const Outcome outcome = tooLong ? Outcome::Error : runCommands(p, QByteArrayView(command).sliced(2));
    if (outcome == Outcome::Ok)
        sendResult(p, ResultCode::Ok);
    else if (outcome == Outcome::Error)
        sendResult(p, ResultCode::Error);
}

SatelliteModem::Outcome SatelliteModem::runCommands(Port& p, QByteArrayView commands)
{
    for (qsizetype at = 0; at < commands.size();) {
        Outcome outcome = Outcome::Ok;
        switch (upper(commands[at++])) {
        case ' ':
            break;
        // D, A and O end the line: what follows is the dial string, or ignored.
        case 'D':
            return dial(p, commands.sliced(at));
        case 'A':
            return answer(p);
        case 'O':
            return numberAt(commands, at, 0) == 0 ? goOnline(p) : Outcome::Error;
        case 'E': {
            const int on = numberAt(commands, at, 0);
            if (on > 1)
                return Outcome::Error;
            p.echo = on == 1;
            break;
        }
        case 'V':  // only verbose results, the form modem::resultLine writes
            if (numberAt(commands, at, 0) != 1)
                return Outcome::Error;
            break;
        case 'Q':  // results are never quiet
            if (numberAt(commands, at, 0) != 0)
                return Outcome::Error;
            break;
        case 'H':
            if (numberAt(commands, at, 0) != 0)
                return Outcome::Error;
            outcome = hangUp(p, QStringLiteral("ATH"));
            break;
        case 'Z':
            numberAt(commands, at, 0);
            outcome = hangUp(p, QStringLiteral("ATZ"));
            resetSettings(p);
            break;
        case 'S':
            outcome = runRegister(p, commands, at);
            break;
        case '&':
            outcome = runAmpersand(p, commands, at);
            break;
        case 'L':  // speaker volume, speaker, which result codes: nothing to choose on this model
        case 'M':
        case 'X':
            numberAt(commands, at, 0);
            break;
        case 'I':
            numberAt(commands, at, 0);
            sendInformation(p, "RCM satellite modem model: " + m_options.profile.title.toLatin1());
            break;
        case '+':
            outcome = runExtended(p, commands, at);
            break;
        case ';':
            break;
        default:
            return Outcome::Error;
        }
        if (outcome != Outcome::Ok)
            return outcome;
    }
    return Outcome::Ok;
}

SatelliteModem::Outcome SatelliteModem::runAmpersand(Port& p, QByteArrayView commands, qsizetype& at)
{
    if (at >= commands.size())
        return Outcome::Error;
    const char letter = upper(commands[at++]);
    const int value = numberAt(commands, at, 0);
    switch (letter) {
    case 'F':
        if (value != 0)
            return Outcome::Error;
        resetSettings(p);
        return Outcome::Ok;
    case 'D':  // &D0: DTR is ignored, the call outlives the program; &D1, &D2: dropping DTR hangs up
        p.dtrHangsUp = value != 0;
        return Outcome::Ok;
    case 'C':  // DCD and flow control: the model behaves as &C1 &K3 whatever is asked
    case 'K':
        return Outcome::Ok;
    default:
        return Outcome::Error;
    }
}

void SatelliteModem::sendInformation(Port& p, const QByteArray& text)
{
    send(p, "\r\n" + text + "\r\n");
}

// The extended commands of the phones' dialects, "+NAME", then "?", "=?",
// "=values" or nothing, up to a ';' or the line's end.
SatelliteModem::Outcome SatelliteModem::runExtended(Port& p, QByteArrayView commands, qsizetype& at)
{
    const modem::Profile& profile = m_options.profile;
    if (!profile.hasNetwork())
        return Outcome::Error;  // a modem without a network has none of them
    QByteArray name;
    while (at < commands.size() && std::isalpha(static_cast<unsigned char>(commands[at])))
        name += upper(commands[at++]);
    QByteArray rest;
    while (at < commands.size() && commands[at] != ';')
        rest += commands[at++];
    rest.replace(' ', QByteArray());
    const bool read = rest == "?";
    const bool test = rest == "=?";
    const bool set = rest.startsWith('=') && !test;
    const QList<QByteArray> values = set ? rest.mid(1).split(',') : QList<QByteArray>{};
    const auto valueAt = [&](int i, int otherwise) {
        bool ok = false;
        const int v = values.value(i).toInt(&ok);
        return ok ? v : otherwise;
    };
    const bool iridium = profile.scale == modem::SignalScale::Bars;
    // Iridium writes "+CSQ:4"; the GSM family "+CSQ: 17,99".
    const QByteArray colon = iridium ? ":" : ": ";
    const int stat = registered() ? 1 : 2;
    if (name == "CBST") {
        if (read)
            sendInformation(p, "+CBST" + colon + p.bearer);
        else if (test)
            sendInformation(p, "+CBST" + colon + "(0-134),(0-1),(0-1)");
        else if (set && values.size() == 3)
            p.bearer = rest.mid(1);
        else
            return Outcome::Error;
        return Outcome::Ok;
    }
    if (name == "CREG") {
        if (read)
            sendInformation(p, "+CREG" + colon + QByteArray::number(p.registrationReports) + ',' +
                                   QByteArray::number(stat));
        else if (test)
            sendInformation(p, "+CREG" + colon + "(0-2)");
        else if (set && valueAt(0, -1) >= 0 && valueAt(0, -1) <= 2)
            p.registrationReports = valueAt(0, 0);
        else
            return Outcome::Error;
        return Outcome::Ok;
    }
    if (name == "CSQ" || (name == "CSQF" && iridium)) {
        if (test) {
            sendInformation(p, "+" + name + colon + (iridium ? "(0-5)" : "(0-31,99),(0-7,99)"));
            return Outcome::Ok;
        }
        if (!rest.isEmpty())
            return Outcome::Error;
        const QByteArray rssi = QByteArray::number(modem::signalFromBars(m_bars, profile.scale));
        sendInformation(p, "+" + name + colon + (iridium ? rssi : rssi + ",99"));
        return Outcome::Ok;
    }
    if (name == "CIER" && iridium) {
        if (read) {
            sendInformation(p, "+CIER:" + QByteArray::number(int(p.indicatorEvents)) + ',' +
                                   QByteArray::number(int(p.signalEvents)) + ',' +
                                   QByteArray::number(int(p.serviceEvents)) + ",0");
            return Outcome::Ok;
        }
        if (test) {
            sendInformation(p, "+CIER:(0-1),(0-1),(0-1),(0-1)");
            return Outcome::Ok;
        }
        if (!set || values.isEmpty() || values.size() > 4)
            return Outcome::Error;
        p.indicatorEvents = valueAt(0, 0) == 1;
        p.signalEvents = valueAt(1, 0) == 1;
        p.serviceEvents = valueAt(2, 0) == 1;
        // Turned on, the indicators say where they stand: after the OK.
        if (p.indicatorEvents)
            QMetaObject::invokeMethod(this, [this, side = p.side] { report(port(side), true, true); },
                                      Qt::QueuedConnection);
        return Outcome::Ok;
    }
    if (name == "CGMI" || name == "CGMM" || name == "GMM") {
        sendInformation(p, profile.title.toLatin1() + " (RCM satellite modem model)");
        return Outcome::Ok;
    }
    return Outcome::Error;
}

SatelliteModem::Outcome SatelliteModem::runRegister(Port& p, QByteArrayView commands, qsizetype& at)
{
    const int index = numberAt(commands, at, -1);
    if (index < 0 || index >= int(p.registers.size()) || at >= commands.size())
        return Outcome::Error;
    int& value = p.registers[std::size_t(index)];
    if (commands[at] == '?') {
        ++at;
        send(p, "\r\n" + QByteArray::number(value).rightJustified(3, '0') + "\r\n");
        return Outcome::Ok;
    }
    if (commands[at] == '=') {
        ++at;
        const int newValue = numberAt(commands, at, 0);
        if (newValue > 255)
            return Outcome::Error;
        value = newValue;
        return Outcome::Ok;
    }
    return Outcome::Error;
}

void SatelliteModem::resetSettings(Port& p)
{
    p.echo = true;
    p.registers = defaultRegisters();
    p.registrationReports = 0;
    p.indicatorEvents = p.signalEvents = p.serviceEvents = false;
    p.dtrHangsUp = true;
}

SatelliteModem::Outcome SatelliteModem::dial(Port& p, QByteArrayView dialString)
{
    const QByteArray number = numberDialled(dialString);
    if (number.isEmpty() || inCall(p))
        return Outcome::Error;
    p.dialled = number;
    ++m_counters.dials;
    if (m_call.state != CallState::Idle) {
        // The far phone is calling this one: it is off the hook.
        sendResult(p, ResultCode::Busy);
        return Outcome::Answered;
    }
    if (m_options.noService || !registered()) {
        sendResult(p, ResultCode::NoDialtone);
        return Outcome::Answered;
    }
    m_call.caller = p.side;
    p.mode = Port::Mode::Dialling;
    setCallState(CallState::Dialling);
    m_setupTimer->start(m_options.callSetupTime);
    return Outcome::Answered;
}

SatelliteModem::Outcome SatelliteModem::answer(Port& p)
{
    if (m_call.state == CallState::Ringing && p.side != m_call.caller) {
        connectCall();
        return Outcome::Answered;
    }
    if (p.mode == Port::Mode::OnlineCommand)
        return Outcome::Error;
    sendResult(p, ResultCode::NoCarrier);  // nothing to answer: no carrier came
    return Outcome::Answered;
}

SatelliteModem::Outcome SatelliteModem::goOnline(Port& p)
{
    if (p.mode != Port::Mode::OnlineCommand)
        return Outcome::Error;
    p.mode = Port::Mode::Data;
    p.lastByteAt = now();
    sendResult(p, ResultCode::Connect);
    return Outcome::Answered;
}

SatelliteModem::Outcome SatelliteModem::hangUp(Port& p, const QString& how)
{
    const bool ringingHere = m_call.state == CallState::Ringing && p.side != m_call.caller;
    if (ringingHere) {
        // Refused, as a phone refuses a call: the caller hears busy.
        sendResult(port(m_call.caller), ResultCode::Busy);
    } else if (!inCall(p)) {
        return Outcome::Ok;
    } else if (m_call.state == CallState::Connected) {
        sendResult(farPort(p), ResultCode::NoCarrier);
    }
    emit hungUp(p.side, how);
    endCall();
    return Outcome::Ok;
}

void SatelliteModem::abortDial(Port& p)
{
    sendResult(p, ResultCode::NoCarrier);
    emit hungUp(p.side, QStringLiteral("aborted"));
    endCall();
}

// ---------------------------------------------------------------------------
// Data mode and the "+++" escape.

void SatelliteModem::takeData(Port& p, QByteArrayView bytes)
{
    const qint64 at = now();
    const int guard = guardTimeMs(p);
    for (const char c : bytes) {
        const bool afterSilence = at - p.lastByteAt >= guard;
        p.lastByteAt = at;
        if (c == modem::kEscapeSequence[0] && afterSilence) {
            releaseHeldPluses(p);
            p.heldPluses = 1;
            p.guard->start(std::chrono::milliseconds(guard));
        } else if (c == modem::kEscapeSequence[0] && p.heldPluses > 0 && p.heldPluses < 3) {
            ++p.heldPluses;
            p.guard->start(std::chrono::milliseconds(guard));
        } else {
            releaseHeldPluses(p);
            p.waiting += c;
        }
    }
    updateFlowControl(p);
}

void SatelliteModem::releaseHeldPluses(Port& p)
{
    if (p.heldPluses == 0)
        return;
    p.waiting += QByteArray(p.heldPluses, modem::kEscapeSequence[0]);
    p.heldPluses = 0;
    p.guard->stop();
}

// The guard time has passed since the last plus: three of them, with silence
// either side, are the escape; fewer are data.
void SatelliteModem::onGuardTimeAfterEscape(Port& p)
{
    if (p.mode != Port::Mode::Data)
        return;
    readPty(p);  // bytes that came after the pluses but are not read yet break the silence
    if (p.guard->isActive())
        return;  // they began another escape
    if (p.heldPluses < 3) {
        releaseHeldPluses(p);
        updateFlowControl(p);
        return;
    }
    p.heldPluses = 0;
    p.mode = Port::Mode::OnlineCommand;
    sendResult(p, ResultCode::Ok);
    flushReports(p);
}

int SatelliteModem::guardTimeMs(const Port& p) const
{
    return p.registers[kGuardTime] * kGuardUnitMs;
}

// ---------------------------------------------------------------------------
// The call.

bool SatelliteModem::inCall(const Port& p) const
{
    return p.mode != Port::Mode::Command;
}

void SatelliteModem::setCallState(CallState state)
{
    if (m_call.state == state)
        return;
    m_call.state = state;
    emit callStateChanged(state);
}

void SatelliteModem::onSetupTimeOver()
{
    if (m_options.busy) {
        sendResult(port(m_call.caller), ResultCode::Busy);
        endCall();
        return;
    }
    m_call.rings = 0;
    setCallState(CallState::Ringing);
    ring();
    if (m_call.state == CallState::Ringing)
        m_ringTimer->start(m_options.ringInterval);
}

void SatelliteModem::ring()
{
    if (m_call.rings >= m_options.ringLimit) {
        sendResult(port(m_call.caller), ResultCode::NoAnswer);
        endCall();
        return;
    }
    ++m_call.rings;
    Port& callee = port(1 - m_call.caller);
    sendResult(callee, ResultCode::Ring);
    // With no program on the line DTR is off, and a modem at &D2 answers nothing.
    const int autoAnswer = callee.registers[kAutoAnswerRings];
    if (autoAnswer > 0 && m_call.rings >= autoAnswer && callee.users > 0)
        connectCall();
}

void SatelliteModem::connectCall()
{
    m_ringTimer->stop();
    for (auto& p : m_ports) {
        p->mode = Port::Mode::Data;
        p->lastByteAt = now();
    }
    m_lastPace = now();
    m_paceTimer->start(std::chrono::milliseconds(kPaceIntervalMs));
    ++m_counters.calls;
    sendResult(port(m_call.caller), ResultCode::Connect);
    sendResult(port(1 - m_call.caller), ResultCode::Connect);
    setCallState(CallState::Connected);
    scheduleRandomDrop();
}

void SatelliteModem::scheduleRandomDrop()
{
    if (m_options.meanTimeBetweenDrops.count() <= 0)
        return;
    std::exponential_distribution<double> untilDrop(1.0 / double(m_options.meanTimeBetweenDrops.count()));
    m_dropTimer->start(std::chrono::milliseconds(qint64(std::min(untilDrop(m_random), double(INT_MAX)))));
}

void SatelliteModem::dropCall()
{
    if (m_call.state == CallState::Idle)
        return;
    ++m_counters.drops;
    for (auto& p : m_ports) {
        if (inCall(*p))
            sendResult(*p, ResultCode::NoCarrier);
    }
    setCallState(CallState::Dropped);
    emit hungUp(-1, QStringLiteral("dropped"));
    endCall();
}

// Both sides back in command mode, the air emptied: what was on its way is lost.
void SatelliteModem::endCall()
{
    m_setupTimer->stop();
    m_ringTimer->stop();
    m_dropTimer->stop();
    m_paceTimer->stop();
    for (auto& p : m_ports) {
        const bool wasOnline = p->mode != Port::Mode::Command;
        p->mode = Port::Mode::Command;
        if (wasOnline)
            QMetaObject::invokeMethod(this, [this, side = p->side] { flushReports(port(side)); },
                                      Qt::QueuedConnection);
        p->heldPluses = 0;
        p->guard->stop();
        p->waiting.clear();
        p->inFlight.clear();
        p->credit = 0;
        updateFlowControl(*p);
    }
    m_call = Call{m_call.state};
    setCallState(CallState::Idle);
}

// ---------------------------------------------------------------------------
// The air.

void SatelliteModem::pace()
{
    const qint64 at = now();
    const qint64 elapsedMs = at - std::exchange(m_lastPace, at);
    for (auto& p : m_ports)
        launch(*p, elapsedMs, at);
    for (auto& p : m_ports) {
        deliver(*p, at);
        updateFlowControl(*p);
    }
}

void SatelliteModem::launch(Port& from, qint64 elapsedMs, qint64 at)
{
    from.credit += double(m_options.airRate) * double(elapsedMs) / 1000.0;
    const qsizetype n = std::min(qsizetype(from.credit), from.waiting.size());
    if (n > 0) {
        from.inFlight.push_back({at + m_options.oneWayDelay.count(), from.waiting.first(n)});
        from.waiting.remove(0, n);
        from.credit -= double(n);
    }
    if (from.waiting.isEmpty())
        from.credit = 0;  // an idle air saves no time for later
}

void SatelliteModem::deliver(Port& from, qint64 at)
{
    Port& to = farPort(from);
    while (!from.inFlight.empty() && from.inFlight.front().arrivesAt <= at) {
        const QByteArray bytes = std::move(from.inFlight.front().bytes);
        from.inFlight.pop_front();
        m_counters.bytesCarried[std::size_t(from.side)] += bytes.size();
        if (to.mode == Port::Mode::Data)
            send(to, bytes);  // in command mode the modem has nowhere to put them
    }
}

qsizetype SatelliteModem::bufferLimit() const
{
    return std::max(1, m_options.bufferLimit);
}

void SatelliteModem::updateFlowControl(Port& p)
{
    if (!p.readable)
        return;
    if (!p.ctsDropped && p.waiting.size() >= bufferLimit()) {
        p.ctsDropped = true;
        p.readable->setEnabled(false);
        ++m_counters.flowControlStops[std::size_t(p.side)];
        emit flowControlChanged(p.side, true);
    } else if (p.ctsDropped && 2 * p.waiting.size() < bufferLimit()) {
        p.ctsDropped = false;
        p.readable->setEnabled(true);
        emit flowControlChanged(p.side, false);
    }
}
