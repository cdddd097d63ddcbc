// One frame of a log, read on its own: for the frame log's rows and detail
// pane, CSV export and `rcm decode` of a frame log. The receive path's own
// steps (RS, decipher and authenticate with the keys given, decode, the
// exactness rules: FrameReceiver in recording mode) without the continuity
// it checks between a sender's frames: a row is read the same whatever rows
// are shown or exported beside it, and a log's rows are any subset, in any
// order.
//
// A frame of a keyed session is ciphertext. Without a key it is not decoded
// at all, and says so: read as plain it would show items nobody sent.
//
// Plain C++20, no Qt.
#pragma once

#include "codec/receive/FrameReceiver.h"

#include "codec/secure/SecureCodec.h"

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rcm {

struct LoggedFrameReading {
    enum class Outcome {
        Read,        // exact (and authentic, keyed): decoded.message is what was sent
        Refused,     // refusal and detail say why
        Enciphered,  // a keyed session's frame and no key: not decoded
        NotAFrame,   // neither 600 nor 510 bytes
    };
    Outcome outcome = Outcome::NotAFrame;
    DecodedBlocks blocks;  // after RS: the corrections (still enciphered on a keyed link)
    // Read: the message. Refused on the plain link: what could be read, for
    // forensic display only. Otherwise empty.
    DecodeResult decoded;
    std::optional<Refusal> refusal;
    std::string detail;
    std::optional<secure::Direction> direction;  // keyed and read: the direction it authenticated in

    bool read() const { return outcome == Outcome::Read; }
};

// One key's codecs for both directions, to read a log with: a log holds the
// frames of both, and a link's endpoint has one direction's receiver only.
// HCTR2 is safe from several threads, so one LogKey may be shared.
class LogKey {
public:
    explicit LogKey(const secure::SecretKey& psk);
    LogKey(const LogKey&) = delete;  // its codecs() point into it
    LogKey& operator=(const LogKey&) = delete;
    // Nothing, with the reason in `error`, when the key file is refused.
    static std::unique_ptr<LogKey> open(const std::string& keyPath, std::string& error);

    const std::vector<const secure::SecureCodec*>& codecs() const { return m_codecs; }
    const std::string& fingerprint() const { return m_fingerprint; }
    // What the session publishes on a broker is sealed with (BrokerSeal.h).
    const secure::SecretKey& brokerKey() const { return m_brokerKey; }

private:
    secure::SecureCodec m_up;
    secure::SecureCodec m_down;
    std::vector<const secure::SecureCodec*> m_codecs;
    std::string m_fingerprint;
    secure::SecretKey m_brokerKey;
};

// `enciphered`: the log says the frame went over a keyed link. `codecs`: one
// per direction the frame may have been sent in (both, for a log); not owned.
LoggedFrameReading readLoggedFrame(std::span<const std::uint8_t> bytes, bool enciphered,
                                   const std::vector<const secure::SecureCodec*>& codecs);
// The same with a log's key, or none.
LoggedFrameReading readLoggedFrame(std::span<const std::uint8_t> bytes, bool enciphered, const LogKey* key);

}  // namespace rcm
