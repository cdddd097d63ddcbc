#pragma once

// A transport made to carry voice beside the commands (docs/protocol.md
// section 7): a stream (the serial modem) in a VoiceSerialLink, datagrams
// (UDP) in a VoiceUdpLink. Null source: idle voice; null sink: received
// voice dropped. On a keyed link the voice is enciphered and authenticated
// with the link's voice keys (codec/voice/SecureVoice.h): what is sent is
// sealed, what is received opened, and a forged or replayed frame is never
// played, only counted and said through `refused`.

#include "link/transport/Link.h"
#include "link/voice/SecureVoiceSink.h"

#include <memory>

class VoiceSink;
class VoiceSource;

namespace rcm::secure {
struct VoiceKeys;
}

struct VoiceSecurity {
    std::shared_ptr<const rcm::secure::VoiceKeys> send;     // null: the plain voice
    std::shared_ptr<const rcm::secure::VoiceKeys> receive;
    SecureVoiceSink::RefusedHandler refused;
};

std::unique_ptr<Link> withVoice(std::unique_ptr<Link> link, std::shared_ptr<VoiceSource> source,
                                std::shared_ptr<VoiceSink> sink, const VoiceSecurity& security = {});
