// What reading the two data blocks of a frame gives: the message, and each
// problem found in it. Filled in by the receive path (codec/receive), the one
// way into a message outside codec/.
#pragma once

#include "codec/frame/Frame.h"
#include "codec/message/Diagnostic.h"
#include "codec/message/Message.h"

namespace rcm {

struct DecodeResult {
    Message message;
    Diagnostics diagnostics;  // problems inside the blocks (corrupt fields, unknown IDs ...)
    Corrections corrected;    // in each codeword, -1 when uncorrectable
    bool ok() const { return corrected.ok(); }
};

}  // namespace rcm
