#pragma once

// A snapshot of one link's counters, sent by value from the link thread to
// whoever displays them. Times are absolute, so the receiver computes ages
// against its own clock when it draws them.

#include <QMetaType>
#include <QtGlobal>

#include "codec/receive/Refusal.h"

#include <algorithm>
#include <array>
#include <numeric>

enum class LinkState : quint8 {
    Closed,     // not started, or stopped
    Waiting,    // open, no good frame received yet
    Connected,  // good frames within the silence timeout
    Lost,       // open but silent longer than the timeout, or the transport is gone
};

// What "the best link" means across stations, higher better: one connected
// station is enough to reach the aircraft; a lost one says more than one
// still waiting; a closed one, nothing.
constexpr int linkRank(LinkState state)
{
    switch (state) {
        case LinkState::Connected:
            return 3;
        case LinkState::Lost:
            return 2;
        case LinkState::Waiting:
            return 1;
        case LinkState::Closed:
            break;
    }
    return 0;
}

struct LinkStatistics {
    LinkState state = LinkState::Closed;

    quint64 framesSent = 0;
    quint64 bytesReceived = 0;         // from the transport, datagrams of any size included
    quint64 framesReceived = 0;        // frames delivered: passed the receive path's acceptance decision
    quint64 framesFromPrediction = 0;  // of those, read with what the receiver expected
    quint64 correctedBytesBlock1 = 0;  // Reed-Solomon corrections over all delivered frames
    quint64 correctedBytesBlock2 = 0;
    quint64 bytesSkipped = 0;          // stream bytes the synchroniser found no frame in
    // Secure link: frames are enciphered and authenticated ("encrypted and
    // authenticated" in the status bar).
    bool secure = false;
    // Frames refused, by reason (codec/receive/Refusal.h): uncorrectable,
    // wrong-size datagrams, forged, not exact, replayed, stale ...
    std::array<quint64, rcm::kRefusalCount> refused{};
    qint64 lastGoodFrameUtcMicros = 0;  // 0: none yet

    // Delay from each ideal tick to the frame handed to the transport; the
    // floor is "within 50 ms of its tick".
    quint64 sendDelaySamples = 0;
    qint64 sendDelayMinMicros = 0;
    qint64 sendDelayMaxMicros = 0;
    qint64 sendDelayTotalMicros = 0;
    quint64 ticksMissed = 0;  // ticks that passed while the thread was busy

    double sendDelayMeanMicros() const
    {
        return sendDelaySamples ? double(sendDelayTotalMicros) / double(sendDelaySamples) : 0.0;
    }
    void addSendDelay(qint64 micros)
    {
        sendDelayMinMicros = sendDelaySamples ? std::min(sendDelayMinMicros, micros) : micros;
        sendDelayMaxMicros = sendDelaySamples ? std::max(sendDelayMaxMicros, micros) : micros;
        sendDelayTotalMicros += micros;
        ++sendDelaySamples;
    }
    quint64 refusedFor(rcm::Refusal r) const { return refused[std::size_t(r)]; }
    quint64 refusedTotal() const { return std::accumulate(refused.begin(), refused.end(), quint64{0}); }
    // -1 when no good frame has arrived yet.
    qint64 lastGoodFrameAgeMicros(qint64 nowUtcMicros) const
    {
        return lastGoodFrameUtcMicros ? nowUtcMicros - lastGoodFrameUtcMicros : -1;
    }

    friend bool operator==(const LinkStatistics&, const LinkStatistics&) = default;
};

Q_DECLARE_METATYPE(LinkState)
Q_DECLARE_METATYPE(LinkStatistics)
