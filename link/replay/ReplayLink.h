#pragma once

// Plays a frame log back as if it were a live transport, so that LinkWorker
// decodes, counts and shows a recorded session exactly as it did the first
// time. The received frames come out of datagramReceived() at their logged
// pace (divided by the speed); every record, the sent ones too, also comes
// out of frameReplayed() for the log view. The console's own sends go
// nowhere: write() refuses them.
//
// A serial frame is replayed without its 90-byte preamble: the worker reads a
// replay as datagrams (one frame each, no synchroniser), and the preamble is
// all that tells the two forms apart. Records of any other length are passed
// on as they are, so the worker rejects them again as it did live.
//
// Time is log time, the UTC microseconds the records carry. Playback follows
// the records' timestamps from one QTimer; the log is indexed and each frame
// read only when it is due, so a day-long log costs its index, not its
// frames. Where the wall clock stepped backwards mid-session, the records
// after the step play at once, in file order.

#include "link/clock/Clock.h"
#include "link/framelog/FrameLogReader.h"
#include "link/transport/Link.h"

#include <memory>

class ReplayLink : public Link {
    Q_OBJECT

public:
    enum class State {
        Closed,
        Playing,
        Paused,
        Finished,  // every record has been played; seek() plays again
    };
    Q_ENUM(State)

    static constexpr double kMinSpeed = 0.25;
    static constexpr double kMaxSpeed = 10.0;

    // Paced by `clock`'s steady time and timers; the system clock when null.
    explicit ReplayLink(const QString& pcapngPath, QObject* parent = nullptr);
    ReplayLink(const QString& pcapngPath, std::shared_ptr<Clock> clock, QObject* parent = nullptr);
    ~ReplayLink() override;

    FrameTransport transport() const override { return FrameTransport::Replay; }
    bool isStream() const override { return false; }
    bool isOpen() const override { return m_open; }
    // "replay rcm-2026-11-22T07-32-00Z.pcapng at 2x"
    QString description() const override;

    QString path() const { return m_path; }
    State state() const { return m_state; }
    bool isPaused() const { return m_paused; }
    double speed() const { return m_speed; }

    // Valid while open.
    int frameCount() const { return m_reader.count(); }
    qint64 startMicros() const;                       // the first record's time
    qint64 endMicros() const { return m_endMicros; }  // the latest record time in the log
    // The record to be played next; frameCount() when finished.
    int nextIndex() const { return m_next; }
    // Where playback stands in log time, advancing between records.
    qint64 positionMicros() const;

public slots:
    // Indexes the log and starts playing from its first record, unless
    // paused before. A log that cannot be read at all is an errorOccurred()
    // and stays closed; one corrupt part-way plays the records before the
    // fault, after an errorOccurred() that says so.
    void open() override;
    void close() override;
    // Always false: a recording has no one to send to.
    bool write(const QByteArray& bytes) override;

    // Paused before open(), the replay opens paused at its first record.
    void setPaused(bool paused);
    void pause() { setPaused(true); }
    void resume() { setPaused(false); }
    // Clamped to [kMinSpeed, kMaxSpeed]; 2 plays a minute of log in 30 s.
    void setSpeed(double speed);
    // Continues from the first record at or after utcMicros (the reader's
    // indexAtOrAfter), keeping the paused state. Before the first record it
    // is the start, past the last it is the end (Finished).
    void seek(qint64 utcMicros);

signals:
    // Every record as logged, both directions, in file order.
    void frameReplayed(const FrameRecord& record);
    // After each record played, and after seek(): where playback stands.
    void positionChanged(qint64 utcMicros, int nextIndex);
    void stateChanged(ReplayLink::State state);
    void speedChanged(double speed);
    // Once each time playback reaches the end of the log (by playing or by
    // seeking past it); not again while it stays there.
    void endOfLog();

private:
    qint64 dueMicros(int index) const;
    void playDue();
    void schedule();
    void updateState();
    void restartClock(qint64 logMicros);

    QString m_path;
    FrameLogReader m_reader;
    std::shared_ptr<Clock> m_clock;
    ClockTimer* m_timer;          // a child
    qint64 m_anchorSteadyMicros = 0;  // the clock's steady time at m_anchorMicros, while playing
    qint64 m_anchorMicros = 0;  // log time when playing (re)started, or where it stopped
    qint64 m_endMicros = 0;
    qint64 m_floorMicros = 0;  // the latest log time played or sought: nothing is due before it
    int m_next = 0;
    double m_speed = 1.0;
    bool m_paused = false;
    bool m_open = false;
    quint64 m_epoch = 0;  // bumped by every control, so playDue() notices one made from a slot
    State m_state = State::Closed;
};
