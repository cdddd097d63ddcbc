#pragma once

// A good frame from the aircraft, as the link thread hands it on: the decoded
// message with what it cost to get it.

#include "codec/frame/Frame.h"
#include "codec/message/Diagnostic.h"
#include "codec/message/Message.h"
#include "link/framelog/FrameLog.h"

#include <QMetaType>

struct ReceivedMessage {
    rcm::Message message;
    rcm::Corrections corrected;  // by Reed-Solomon, in each codeword
    // Problems inside the blocks; the message keeps every item read correctly.
    rcm::Diagnostics diagnostics;
    qint64 utcMicros = 0;  // when the frame was complete
    FrameTransport transport = FrameTransport::Serial;
};

Q_DECLARE_METATYPE(ReceivedMessage)
