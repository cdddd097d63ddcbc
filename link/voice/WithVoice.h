#pragma once

// A transport made to carry voice beside the commands (docs/protocol.md
// section 7): a stream (the serial modem) in a VoiceSerialLink, datagrams
// (UDP) in a VoiceUdpLink. Null source: idle voice; null sink: received
// voice dropped.

#include "link/transport/Link.h"

#include <memory>

class VoiceSink;
class VoiceSource;

std::unique_ptr<Link> withVoice(std::unique_ptr<Link> link, std::shared_ptr<VoiceSource> source,
                                std::shared_ptr<VoiceSink> sink);
