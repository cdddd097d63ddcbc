#include "codec/receive/LoggedFrameReading.h"

#include "codec/message/MessageDecoder.h"
#include "codec/secure/BrokerSeal.h"

namespace rcm {

LogKey::LogKey(const secure::SecretKey& psk)
    : m_up(psk, secure::Direction::GcsToUa),
      m_down(psk, secure::Direction::UaToGcs),
      m_codecs{&m_up, &m_down},
      m_fingerprint(secure::fingerprint(psk)),
      m_brokerKey(secure::deriveBrokerKey(psk))
{
}

std::unique_ptr<LogKey> LogKey::open(const std::string& keyPath, std::string& error)
{
    const std::optional<secure::SecretKey> psk = secure::readKeyFile(keyPath, error);
    if (!psk)
        return nullptr;
    return std::make_unique<LogKey>(*psk);
}

namespace {

LoggedFrameReading judged(std::span<const std::uint8_t> bytes, const std::vector<const secure::SecureCodec*>& codecs)
{
    LoggedFrameReading reading;
    FrameReceiver::Options options;
    options.mode = FrameReceiver::Mode::Recording;
    options.keys.codecs = codecs;
    options.predictions = false;  // one frame alone: nothing to predict it from
    FrameReceiver receiver(options, [&](const ReceivedFrame& f) {
        reading.outcome = f.delivered() ? LoggedFrameReading::Outcome::Read : LoggedFrameReading::Outcome::Refused;
        reading.blocks = f.blocks;
        reading.decoded = f.decoded;
        reading.decoded.corrected.block1 = f.blocks.corrected.block1;
        reading.decoded.corrected.block2 = f.blocks.corrected.block2;
        reading.refusal = f.refusal;
        reading.detail = f.detail;
        reading.direction = f.direction;
    });
    receiver.receive(bytes);
    return reading;
}

}  // namespace

LoggedFrameReading readLoggedFrame(std::span<const std::uint8_t> bytes, bool enciphered,
                                   const std::vector<const secure::SecureCodec*>& codecs)
{
    if (bytes.size() != kFrameSize && bytes.size() != kDatagramSize)
        return {};
    if (enciphered && codecs.empty()) {
        LoggedFrameReading reading;
        reading.outcome = LoggedFrameReading::Outcome::Enciphered;
        reading.blocks = decodeCodewords(bytes.last<kDatagramSize>());
        reading.decoded.corrected.block1 = reading.blocks.corrected.block1;
        reading.decoded.corrected.block2 = reading.blocks.corrected.block2;
        return reading;
    }
    if (enciphered)
        return judged(bytes, codecs);
    // Marked plain. A log written before frames were marked may still hold
    // a keyed session's: with a key, what plain reading refuses is tried
    // deciphered as well.
    LoggedFrameReading plain = judged(bytes, {});
    if (plain.read() || codecs.empty())
        return plain;
    LoggedFrameReading keyed = judged(bytes, codecs);
    return keyed.read() ? keyed : plain;
}

LoggedFrameReading readLoggedFrame(std::span<const std::uint8_t> bytes, bool enciphered, const LogKey* key)
{
    static const std::vector<const secure::SecureCodec*> none;
    return readLoggedFrame(bytes, enciphered, key ? key->codecs() : none);
}

}  // namespace rcm
