#include "codec/cli/KeyedReceive.h"

#include <cstdio>

namespace rcm::cli {

std::unique_ptr<Keyed> loadKeyed(const Options& o)
{
    using namespace rcm::secure;
    std::string error;
    const std::optional<SecretKey> psk = readKeyFile(o.key, error);
    if (!psk) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return nullptr;
    }
    auto k = std::make_unique<Keyed>();
    if (o.direction) {
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, *o.direction));
    } else {
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, Direction::GcsToUa));
        k->codecs.push_back(std::make_unique<SecureCodec>(*psk, Direction::UaToGcs));
    }
    if (!o.replayState.empty()) {
        ReplayGuard::Options g;
        g.stateFile = o.replayState;
        g.keyFingerprint = fingerprint(*psk);
        g.windowSeconds = o.window.value_or(kDefaultWindowSeconds);
        try {
            k->guard = std::make_unique<ReplayGuard>(g);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "rcm: %s\n", e.what());
            return nullptr;
        }
        if (!k->guard->notice().empty())
            std::fprintf(stderr, "rcm: %s\n", k->guard->notice().c_str());
    }
    return k;
}

KeyedResult openKeyed(Keyed& k, const rcm::DecodedBlocks& blocks)
{
    using namespace rcm::secure;
    KeyedResult r;
    if (k.guard) {
        Opened o = openFrame(*k.codecs.front(), k.guard.get(), blocks);
        r.direction = k.codecs.front()->direction();
        if (!o.persistError.empty() && !k.persistWarned) {
            std::fprintf(stderr, "rcm: warning: %s\n", o.persistError.c_str());
            k.persistWarned = true;
        }
        r.accepted = o.accepted;
        r.decoded = std::move(o.decoded);
        r.rejection = o.rejection.value_or(Rejection::Forged);
        r.detail = std::move(o.detail);
        return r;
    }
    // A frame authenticates in at most one direction (the other deciphers
    // it to random bytes), so trying both names the one it was sent in.
    for (const auto& codec : k.codecs) {
        Authenticated a = codec->decryptBlocks(blocks);
        if (a.authentic) {
            r.accepted = true;
            r.decoded = std::move(a.decoded);
            r.direction = codec->direction();
            return r;
        }
        if (a.rejection == Rejection::Plaintext)
            r.rejection = Rejection::Plaintext;
        r.detail = k.codecs.size() == 1 ? a.detail : "sent neither GCS->UA nor UA->GCS with this key";
    }
    if (r.rejection == Rejection::Plaintext)
        r.detail = "an unencrypted message on a keyed link";
    return r;
}

}  // namespace rcm::cli
