#pragma once

// A satellite phone's modem on a serial port (Hayes/V.250 AT commands):
// the call is the link. open() makes sure the modem is in command mode (a
// modem still in a call from an earlier session is escaped and hung up),
// initialises it with the init string and its profile's set-up (the data
// bearer, modem::Profile), reads its registration and signal, and dials
// once the phone is registered with signal, never before (or, on the
// aircraft's side, waits for RING and answers); opened() is said when
// CONNECT comes, closed() when the call ends. A call that drops, seen from
// "NO CARRIER" or from the DCD pin, whichever comes first, is redialled with
// a doubling delay up to a limit, registration and signal read again first;
// a call shorter than minimumCallDuration counts as a failed attempt, so a
// call that connects and drops at once is not redialled for ever. close(),
// and destroying the link, hang up with the escape sequence and ATH, so that
// no call is left open (and billed); the hang-up blocks the link's thread
// for at most hangUpBound().
//
// Every change of the call is said in statusChanged() for the status bar and
// the event log ("dialling 881612345678", "connected at 9600 bit/s after
// 14 s", "call ended after 12 min 3 s, 13 min billed, cost 15.60 USD"), and
// the phone's service in serviceChanged(); a call that drops, a dial that
// cannot get through and a phone with no service to dial on are errors
// (errorOccurred), once per outage.

#include "link/transport/LinkWrapper.h"
#include "link/transport/ModemProfile.h"
#include "link/transport/ModemResultCode.h"

#include <QByteArray>

#include <chrono>
#include <cstdint>
#include <memory>

class Clock;
class ClockTimer;
class SerialLink;

class ModemLink : public LinkWrapper {
    Q_OBJECT

public:
    using Milliseconds = std::chrono::milliseconds;

    struct Options {
        // Sent once the port opens, before dialling or waiting for a call. The
        // profile needs verbose result codes (V1); the rest is the phone's.
        QByteArray initString = "ATE0V1&C1&D2";
        // The phone: its set-up after the init string, how it tells its
        // registration and signal.
        modem::Profile profile = modem::defaultProfile();
        // ATD<number>. Empty: this side answers (RING -> ATA); a modem set
        // to answer by itself (ATS0=1 in the init string) is followed too.
        QString number;
        Milliseconds commandTimeout{5000};  // OK to the init string, to ATA
        // The first "AT" at start-up: a modem that does not answer within
        // this is taken to be in a call still, and escaped and hung up.
        Milliseconds probeTimeout{1500};
        // Registration and signal asked again this often while the phone
        // has no service (its own reports end the wait sooner).
        Milliseconds servicePollInterval{3000};
        Milliseconds dialTimeout{90000};    // ATD to CONNECT or a refusal: a satellite call takes tens of seconds
        Milliseconds guardTime{1000};       // silence around "+++": the modem's S12 (50 = 1 s)
        Milliseconds hangUpTimeout{2000};   // the modem's OK after "+++" (beyond the guard time) and after ATH
        Milliseconds redialDelay{10000};    // before the first redial; doubled for each next one
        Milliseconds redialDelayLimit{160000};
        // The time its timeouts, polls, redials and call lengths run on;
        // null: the SystemClock.
        std::shared_ptr<Clock> clock;
        int redialAttempts = 5;  // in a row, before giving up; 0: never redial
        // A call that ends sooner counts as a failed attempt: the redials in
        // a row start again from the first only after a call this long.
        Milliseconds minimumCallDuration{30000};
        // Poll the DCD pin while connected (a real port with &C1). A
        // pseudo-terminal has no pins: the poll then stops by itself.
        bool watchCarrierDetect = true;
        Milliseconds carrierPollInterval{250};
        // The call's price per started minute, for the operator; 0: not shown.
        double costPerMinute = 0;
        QString costCurrency;  // "USD": said after every cost
    };

    enum class CallState {
        Closed,
        Probing,            // "AT" at start-up: is the modem in command mode?
        Initialising,       // the init string and the profile's set-up
        CheckingService,    // AT+CREG?, AT+CSQ
        WaitingForService,  // not registered, or no signal: no ATD
        Dialling,
        AwaitingCall,
        Answering,
        Connected,
        HangingUp,
        WaitingToRedial,
        GaveUp
    };
    Q_ENUM(CallState)

    ModemLink(std::unique_ptr<SerialLink> serial, Options options, QObject* parent = nullptr);
    ~ModemLink() override;

    bool isOpen() const override;
    bool isConnecting() const override;
    QString description() const override;

    CallState callState() const { return m_state; }
    // The rate CONNECT gave (0 when none), and calls dialled and answered since open().
    int connectRate() const { return m_rate; }
    int calls() const { return m_calls; }
    // What the phone last said of its service.
    const modem::Service& service() const { return m_service; }
    // Calls dialled: ATD commands sent since open().
    int dials() const { return m_dials; }
    // The longest close() or the destructor blocks the link's thread.
    Milliseconds hangUpBound() const;

public slots:
    void open() override;
    void close() override;
    bool write(const QByteArray& bytes) override;

private:
    SerialLink& port() const;
    bool relaysOpenAndClose() const override { return false; }
    void innerOpened() override;
    void innerClosed() override;
    void innerBytesReceived(const QByteArray& bytes) override;

    void setState(CallState state, const QString& status);
    void sendCommand(const QByteArray& command, CallState state, Milliseconds timeout, const QString& status);
    void dial();
    void probe();
    void escapeStaleCall();
    void initialise();
    void nextSetupCommand();
    void checkService();
    void nextServiceQuery();
    void serviceKnown();
    void takeServiceLine(const QByteArray& line);
    void giveUp(const QString& why);
    void takeLines(const QByteArray& bytes);
    void result(const modem::Result& result);
    void connected(int rate);
    void timedOut();
    // The call did not come up (BUSY, NO ANSWER, a time limit) or went down.
    void failed(const QString& what);
    void fail(const QString& message);  // the outage's first failure is an error, later ones statuses
    void callEnded(const QString& why);
    void scheduleRedial(const QString& what);
    void pollCarrier();
    // The escape ("+++" between guard times) and ATH; with dropDtr, DTR
    // dropped after them should the modem not have answered.
    void hangUp(bool dropDtr = true);
    void waitFor(Milliseconds duration, bool untilOk);
    QString callSummary() const;
    QString cost(double amount) const;

    Options m_options;
    CallState m_state = CallState::Closed;
    bool m_wanted = false;        // open() asked for, close() not since
    bool m_failureShown = false;  // this outage's error was said; the next ones are statuses
    bool m_okSeen = false;        // for hangUp(): the modem said OK
    bool m_initialised = false;   // the init string and set-up were taken since the port opened
    bool m_serviceReported = false;  // this wait for service was said as an error
    QList<QByteArray> m_pending;  // set-up commands or service queries still to send
    QByteArray m_command;         // the command waiting for its answer
    modem::Service m_service;
    bool m_serviceKnownOnce = false;  // serviceChanged() said at least once
    QString m_lastServiceWait;        // why the console waits for service, as last said
    QByteArray m_line;            // a result line, until its CR LF
    QByteArray m_dataTail;        // the end of the data so far: NO CARRIER may be split across reads
    int m_rate = 0;
    int m_calls = 0;
    int m_attempt = 0;            // redials in a row since the last call that lasted
    int m_dials = 0;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_timeout;        // a command's or a dial's time limit
    ClockTimer* m_redial;
    ClockTimer* m_servicePoll;
    ClockTimer* m_carrierPoll;    // re-armed after each look at the pins
    std::int64_t m_sinceMicros = -1;  // steady time of this dial's or this call's start; -1: none yet
    qint64 sinceMs() const;
};
