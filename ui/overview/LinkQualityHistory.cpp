#include "ui/overview/LinkQualityHistory.h"

namespace {

constexpr qint64 kMinuteMicros = 60'000'000;

quint64 corrected(const LinkStatistics& s)
{
    return s.correctedBytesBlock1 + s.correctedBytesBlock2;
}

}  // namespace

LinkQualityHistory::LinkQualityHistory(std::chrono::milliseconds frameInterval)
    : m_interval(std::chrono::duration_cast<std::chrono::microseconds>(frameInterval).count())
{
}

void LinkQualityHistory::clear()
{
    m_minutes.clear();
    m_started = false;
}

quint64 LinkQualityHistory::lostSinceFirstFrame(qint64 nowUtcMicros, const LinkStatistics& s) const
{
    if (!s.lastGoodFrameUtcMicros || !m_firstGoodMicros || s.framesReceived == 0)
        return 0;
    // Up to the last good frame: the intervals it spans, less the frames that came.
    const qint64 spanned = (s.lastGoodFrameUtcMicros - m_firstGoodMicros + m_interval / 2) / m_interval + 1;
    const qint64 through = std::max<qint64>(0, spanned - qint64(s.framesReceived));
    // Since then: each frame half an interval overdue.
    const qint64 silent = std::max<qint64>(0, (nowUtcMicros - s.lastGoodFrameUtcMicros - m_interval / 2) / m_interval);
    return quint64(through + silent);
}

void LinkQualityHistory::sample(qint64 nowUtcMicros, const LinkStatistics& s)
{
    if (s.state == LinkState::Closed)
        return;
    const bool wentBack = m_started && (s.framesReceived < m_lastGood || corrected(s) < m_lastCorrected);
    if (!m_started || wentBack) {
        // A new link: its counters start from its own zero.
        m_started = true;
        m_firstGoodMicros = 0;
        m_lastCorrected = 0;
        m_lastGood = 0;
        m_lastLost = 0;
    }
    if (!m_firstGoodMicros && s.framesReceived > 0) {
        // The first good frame seen: it and any before it in this snapshot
        // came at one per interval up to its time.
        m_firstGoodMicros = s.lastGoodFrameUtcMicros - qint64(s.framesReceived - 1) * m_interval;
    }
    const quint64 lost = lostSinceFirstFrame(nowUtcMicros, s);
    Minute& minute = minuteAt(nowUtcMicros);
    minute.correctedBytes += corrected(s) - m_lastCorrected;
    minute.goodFrames += s.framesReceived - m_lastGood;
    minute.lostFrames += lost > m_lastLost ? lost - m_lastLost : 0;
    m_lastCorrected = corrected(s);
    m_lastGood = s.framesReceived;
    m_lastLost = std::max(lost, m_lastLost);
}

LinkQualityHistory::Minute& LinkQualityHistory::minuteAt(qint64 utcMicros)
{
    const qint64 start = utcMicros - utcMicros % kMinuteMicros;
    if (m_minutes.empty() || m_minutes.back().startUtcMicros != start) {
        m_minutes.push_back(Minute{start});
        while (m_minutes.size() > std::size_t(kMinutes) ||
               m_minutes.front().startUtcMicros <= start - kMinutes * kMinuteMicros)
            m_minutes.pop_front();
    }
    return m_minutes.back();
}
