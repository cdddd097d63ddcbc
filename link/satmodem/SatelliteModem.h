#pragma once

// The pair of satellite phone modems between the console and the aircraft,
// for rehearsals and tests: each side is a pseudo-terminal that behaves like a
// Hayes/V.250 modem (AT commands, RING, CONNECT, "+++" escape, NO CARRIER),
// and a call between them carries bytes at the satellite's rate with its
// delay. Side 0 is the ground station's phone, side 1 the aircraft's; either
// may dial the other. The dialect, the timing and the choices made where real
// modems differ are in docs/modem.md.
//
// It runs on its clock (Options::clock; the SystemClock, real time, unless
// told) in the thread that owns it: programs on the ptys see a modem that
// answers as fast, and carries bytes as slowly, as the options say.

#include "link/clock/Clock.h"
#include "link/transport/ModemProfile.h"
#include "link/transport/ModemResultCode.h"

#include <QByteArray>
#include <QObject>
#include <QString>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <random>
#include <vector>

class QSocketNotifier;

class SatelliteModem : public QObject {
    Q_OBJECT

public:
    enum Side : int { Ground = 0, Aircraft = 1 };

    // Dropped is said on its way to Idle, when the network ended the call.
    enum class CallState { Idle, Dialling, Ringing, Connected, Dropped };
    Q_ENUM(CallState)

    struct Options {
        std::chrono::milliseconds callSetupTime{8000};  // ATD to the far side's first RING
        std::chrono::milliseconds oneWayDelay{1500};    // a byte on the air to the far side
        int airRate = 1200;                             // bytes a second each way
        int connectRate = 9600;                         // as CONNECT reports it
        // Bytes a sender may have waiting for the air before its CTS drops
        // (the model stops reading its pty); it rises below half of this.
        int bufferLimit = 1200;
        std::chrono::milliseconds meanTimeBetweenDrops{0};  // 0: calls never drop by themselves
        quint32 seed = 1;                                   // of the random drops
        bool busy = false;       // the far side is busy: BUSY after the set-up time
        bool noService = false;  // no network ever: not registered, no signal, NO DIALTONE at once
        // The phones' dialect: the set-up commands they take, how they
        // answer AT+CREG? and AT+CSQ, and whether they have +CIER/+CIEV.
        modem::Profile profile = modem::defaultProfile();
        // The sky over both phones, as time goes: from `at` after open(),
        // `bars` of signal (0..5; 0: no service, not registered). Before the
        // first step, and with none, 4 bars. A call whose signal goes to 0
        // drops.
        struct ServiceStep {
            std::chrono::milliseconds at{0};
            int bars = 0;
        };
        std::vector<ServiceStep> service;
        int ringLimit = 6;       // rings unanswered before the caller gets NO ANSWER
        std::chrono::milliseconds ringInterval{3000};
        // What its times and timers run on; null: the SystemClock.
        std::shared_ptr<Clock> clock = nullptr;
    };

    struct Counters {
        int dials = 0;  // ATD commands that started a call or were refused by the network
        int calls = 0;  // calls connected
        int drops = 0;  // calls the network ended (random drops, dropCall())
        std::array<qint64, 2> bytesCarried{};     // [side]: bytes the air delivered from that side
        std::array<int, 2> flowControlStops{};    // [side]: times that side's CTS dropped
    };

    explicit SatelliteModem(Options options, QObject* parent = nullptr);
    ~SatelliteModem() override;

    // Opens both pseudo-terminals, raw; false, with the reason, when it cannot.
    bool open(QString* error);
    // "/dev/pts/N", what a program opens to use that side's modem.
    QString device(int side) const;

    const Options& options() const { return m_options; }
    const Counters& counters() const { return m_counters; }
    CallState callState() const { return m_call.state; }
    // The number `side` last dialled, as typed after ATD (T or P left off).
    QByteArray dialledNumber(int side) const;
    // The signal now, 0..5; 0 is no service.
    int signalBars() const { return m_bars; }
    // The service script in the form satmodem's --service takes,
    // "0:0,10:4,60:1"; nothing, the reason in *error, when it does not parse.
    static std::optional<std::vector<Options::ServiceStep>> parseService(const QString& text, QString* error);

public slots:
    // The network loses the call (a rehearsal's call-drop fault): NO CARRIER
    // to every side in it. Nothing happens when there is no call.
    void dropCall();
    // The signal over both phones from now on, 0..5 (0: no service), as the
    // service script sets it; for tests and rehearsals.
    void setSignalBars(int bars);

signals:
    void callStateChanged(SatelliteModem::CallState state);
    // A command line as `side` typed it, "ATE0S0=1", before it runs.
    void commandReceived(int side, const QByteArray& command);
    void resultSent(int side, modem::Result result);
    // The call ended because `side` hung up, `how`: "ATH", "ATZ", "slave
    // closed" (the program on its pty went away: DTR dropped), "aborted" (a
    // key pressed while dialling); side -1 and "dropped" when the network
    // ended it.
    void hungUp(int side, const QString& how);
    // `side`'s CTS dropped (stopped) or rose again.
    void flowControlChanged(int side, bool stopped);
    // The signal changed (the service script): 0..5, 0 no service.
    void signalChanged(int bars);
    // The program on `side`'s pty went away (DTR dropped) and the modem has
    // acted on it: hung up under &D1/&D2, kept the call under &D0.
    void userGone(int side);

private:
    struct Port;
    struct Call {
        CallState state = CallState::Idle;
        int caller = -1;
        int rings = 0;
    };
    enum class Outcome { Ok, Error, Answered };  // of a command line; Answered: its result is sent

    Port& port(int side) { return *m_ports[std::size_t(side)]; }
    Port& farPort(const Port& p) { return port(1 - sideOf(p)); }
    int sideOf(const Port& p) const;
    // Milliseconds since open() (or since it was made).
    qint64 now() const { return (m_clock->steadyMicros() - m_openedSteadyMicros) / 1000; }

    // The ptys and who has them open.
    bool openPort(int side, QString* error);
    void readUserOpensAndCloses();
    void forgetUser(Port& p);
    void onUserGone(int side);
    void readPty(Port& p);
    void takeInput(Port& p, QByteArrayView bytes);
    void send(Port& p, const QByteArray& bytes);
    void sendResult(Port& p, modem::ResultCode code);
    void flushToUser(Port& p);

    // Command mode.
    void takeCommandByte(Port& p, char c);
    void runCommandLine(Port& p, const QByteArray& line, bool tooLong);
    Outcome runCommands(Port& p, QByteArrayView commands);
    Outcome runAmpersand(Port& p, QByteArrayView commands, qsizetype& at);
    Outcome runRegister(Port& p, QByteArrayView commands, qsizetype& at);
    Outcome runExtended(Port& p, QByteArrayView commands, qsizetype& at);
    void sendInformation(Port& p, const QByteArray& text);
    // Unsolicited reports of registration and signal; held while in data
    // mode (the latest of each) and said on the return to command mode.
    void report(Port& p, bool registrationChanged, bool signalChanged);
    void flushReports(Port& p);
    void applyService();
    bool registered() const { return m_bars > 0; }
    void resetSettings(Port& p);
    Outcome dial(Port& p, QByteArrayView dialString);
    Outcome answer(Port& p);
    Outcome goOnline(Port& p);
    Outcome hangUp(Port& p, const QString& how);
    void abortDial(Port& p);

    // Data mode and the "+++" escape.
    void takeData(Port& p, QByteArrayView bytes);
    void releaseHeldPluses(Port& p);
    void onGuardTimeAfterEscape(Port& p);
    int guardTimeMs(const Port& p) const;

    // The call.
    void onSetupTimeOver();
    void ring();
    void connectCall();
    void endCall();
    bool inCall(const Port& p) const;
    void setCallState(CallState state);
    void scheduleRandomDrop();

    // The air.
    void pace();
    void launch(Port& from, qint64 elapsedMs, qint64 at);
    void deliver(Port& from, qint64 at);
    void updateFlowControl(Port& p);
    qsizetype bufferLimit() const;

    Options m_options;
    Counters m_counters;
    Call m_call;
    std::array<std::unique_ptr<Port>, 2> m_ports;
    int m_inotify = -1;  // opens and closes of the slaves by their users
    std::unique_ptr<QSocketNotifier> m_inotifyNotifier;
    std::shared_ptr<Clock> m_clock;
    qint64 m_openedSteadyMicros = 0;
    qint64 m_lastPace = 0;
    ClockTimer* m_setupTimer;
    ClockTimer* m_ringTimer;
    ClockTimer* m_dropTimer;
    ClockTimer* m_paceTimer;
    ClockTimer* m_serviceTimer;
    std::size_t m_serviceStep = 0;  // the next step of the service script
    int m_bars = 4;
    std::mt19937 m_random;
};
