#include "link/voice/WithVoice.h"

#include "codec/voice/SecureVoice.h"
#include "link/clock/Clock.h"
#include "link/voice/SecureVoiceSource.h"
#include "link/voice/VoiceEncoderSource.h"
#include "link/voice/VoiceSerialLink.h"
#include "link/voice/VoiceUdpLink.h"

std::unique_ptr<Link> withVoice(std::unique_ptr<Link> link, std::shared_ptr<VoiceSource> source,
                                std::shared_ptr<VoiceSink> sink, const VoiceSecurity& security)
{
    const auto clock = std::make_shared<SystemClock>();
    if (security.send) {
        // Idle frames to seal when nobody may speak.
        if (!source)
            source = std::make_shared<VoiceEncoderSource>();
        source = std::make_shared<SecureVoiceSource>(std::move(source), *security.send, clock);
    } else if (source) {
        source->setFramesPerPacket(1);
    }
    if (security.receive)
        sink = std::make_shared<SecureVoiceSink>(std::move(sink), *security.receive, clock, security.refused);
    if (link->isStream())
        return std::make_unique<VoiceSerialLink>(std::move(link), std::move(source), std::move(sink));
    auto udp = std::make_unique<VoiceUdpLink>(std::move(link), std::move(source), std::move(sink));
    if (security.send)
        udp->setFraming(rcm::voice::kSecureFrameBytes, int(rcm::voice::kSecureFramesPerSecond));
    return udp;
}
