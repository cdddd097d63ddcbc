#include "link/broker/SequenceCheck.h"

#include <algorithm>

SequenceCheck::Result SequenceCheck::check(const OpenedMessage& message)
{
    Seen& seen = m_topics[message.topic];
    if (message.where &&
        (message.where->kind == BrokerTopics::Kind::Frames || message.where->kind == BrokerTopics::Kind::Events))
        return checkStream(message, seen);
    if (message.will) {
        if (message.seq == seen.willAnnounced && message.seq != 0) {
            if (seen.willTaken)
                return Result::Duplicate;
            seen.willTaken = true;
            return Result::Fresh;
        }
        // A will set after every report we read (we joined late, or it
        // came before its first report reached us).
        if (message.seq > seen.newest) {
            seen.newest = message.seq;
            seen.willAnnounced = message.seq;
            seen.willTaken = true;
            return Result::Fresh;
        }
        return message.seq == seen.newest ? Result::Duplicate : Result::Replayed;
    }
    if (message.seq == seen.newest)
        return Result::Duplicate;
    if (message.seq < seen.newest)
        return Result::Replayed;
    seen.newest = message.seq;
    if (message.willSeq != seen.willAnnounced) {
        seen.willAnnounced = message.willSeq;
        seen.willTaken = false;
    }
    return Result::Fresh;
}

QString SequenceCheck::refusal(const OpenedMessage& message, qint64 newest)
{
    return QStringLiteral("replayed: %1's message %2 on %3 is not newer than %4, read before")
        .arg(message.station)
        .arg(message.seq)
        .arg(message.topic)
        .arg(newest);
}

SequenceCheck::Result SequenceCheck::checkStream(const OpenedMessage& message, Seen& seen)
{
    if (seen.recent.count(message.seq))
        return Result::Duplicate;
    // Older than every number remembered: from before this reader's time, or
    // too old to tell; either way not news.
    if (!seen.recent.empty() && message.seq < *seen.recent.begin())
        return Result::Replayed;
    seen.recent.insert(message.seq);
    if (seen.recent.size() > kStreamWindow)
        seen.recent.erase(seen.recent.begin());
    seen.newest = std::max(seen.newest, message.seq);
    return Result::Fresh;
}
