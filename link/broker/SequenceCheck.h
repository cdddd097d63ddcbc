#pragma once

// The part of reading a verified message that needs to know what came
// before: on each topic a station's messages are taken in increasing number
// (BrokerEnvelope's seq) only, so that a recorded message published again,
// even with its signature whole, is refused as replayed.
//
// Three exceptions, all of the broker's or the client library's making, all
// harmless:
//   - the same number again on the topic (a retained message sent again when
//     a client subscribes anew, a QoS 1 message delivered twice) is a
//     duplicate: dropped, not refused;
//   - on a stream (frames, events) a message the publisher's client sent
//     again after a reconnection, under the number it had then, may come
//     after newer ones: one not yet seen, and no older than the oldest of
//     the last kStreamWindow numbers taken, is taken (a frame's own number,
//     FrameReport::seq, then tells whether it is news), one seen is a
//     duplicate. Reports of state
//     (station, state, statistics) are taken in increasing number only: an
//     older one would put back what is no longer so;
//   - a station's will is numbered when it is set, before the reports that
//     follow; each report says which will is set now (willSeq), and that
//     will is taken once, whenever the broker publishes it.

#include "link/broker/BrokerEnvelope.h"

#include <QHash>
#include <QString>

#include <set>

class SequenceCheck {
public:
    enum class Result { Fresh, Duplicate, Replayed };
    // The numbers remembered on a stream's topic: more than a publisher's
    // backlog (SessionPublisher keeps 1,200 frames) can send again.
    static constexpr std::size_t kStreamWindow = 2048;

    // For a verified message; records it when it is fresh. Replayed: the
    // caller refuses it (refusal() says why).
    Result check(const OpenedMessage& message);
    static QString refusal(const OpenedMessage& message, qint64 newest);
    // The newest number taken on `topic`, 0 for none.
    qint64 newest(const QString& topic) const { return m_topics.value(topic).newest; }
    void clear() { m_topics.clear(); }

private:
    struct Seen {
        qint64 newest = 0;
        qint64 willAnnounced = 0;  // the station's will as its newest report named it
        bool willTaken = false;
        std::set<qint64> recent;  // streams: the last kStreamWindow numbers taken
    };
    Result checkStream(const OpenedMessage& message, Seen& seen);
    QHash<QString, Seen> m_topics;
};
