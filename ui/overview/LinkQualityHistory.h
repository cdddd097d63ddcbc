#pragma once

// The link's quality minute by minute, for the overview's plot: bytes
// Reed-Solomon corrected and status frames lost in each UTC minute of the
// last hour. Fed a snapshot of the link's statistics every second or so
// (sample()), it keeps differences, not snapshots.
//
// A frame is lost when it did not arrive good: the aircraft sends a status
// frame once per interval, so from the first good frame on, every interval
// without one (a frame beyond correction, refused, or never heard) is one
// lost frame. A frame counts as lost once it is half an interval late, so a
// silence counts as it goes on, not only when the link comes back.

#include "link/session/LinkStatistics.h"

#include <chrono>
#include <deque>

class LinkQualityHistory {
public:
    struct Minute {
        qint64 startUtcMicros = 0;  // the UTC minute this covers
        quint64 correctedBytes = 0;
        quint64 lostFrames = 0;
        quint64 goodFrames = 0;
        friend bool operator==(const Minute&, const Minute&) = default;
    };
    static constexpr int kMinutes = 60;

    explicit LinkQualityHistory(std::chrono::milliseconds frameInterval = std::chrono::milliseconds(1000));

    // The link's statistics as they are at `nowUtcMicros`. A closed link adds
    // nothing; counters that went back (a new link) start a new count.
    void sample(qint64 nowUtcMicros, const LinkStatistics& statistics);
    void clear();

    // Oldest first, at most kMinutes, only minutes that had a sample.
    const std::deque<Minute>& minutes() const { return m_minutes; }

    // Frames lost from the first good frame of this link up to `nowUtcMicros`.
    quint64 lostSinceFirstFrame(qint64 nowUtcMicros, const LinkStatistics& statistics) const;

private:
    Minute& minuteAt(qint64 utcMicros);

    qint64 m_interval;
    std::deque<Minute> m_minutes;
    bool m_started = false;
    qint64 m_firstGoodMicros = 0;
    quint64 m_lastCorrected = 0;
    quint64 m_lastGood = 0;
    quint64 m_lastLost = 0;
};
