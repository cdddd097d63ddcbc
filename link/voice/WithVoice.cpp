#include "link/voice/WithVoice.h"

#include "link/voice/VoiceSerialLink.h"
#include "link/voice/VoiceUdpLink.h"

std::unique_ptr<Link> withVoice(std::unique_ptr<Link> link, std::shared_ptr<VoiceSource> source,
                                std::shared_ptr<VoiceSink> sink)
{
    if (link->isStream())
        return std::make_unique<VoiceSerialLink>(std::move(link), std::move(source), std::move(sink));
    return std::make_unique<VoiceUdpLink>(std::move(link), std::move(source), std::move(sink));
}
