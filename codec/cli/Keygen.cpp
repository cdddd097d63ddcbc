#include "codec/cli/Keygen.h"

#include "codec/secure/StationSigningKey.h"

#include <sys/stat.h>

#include <cstdio>

namespace rcm::cli {

int keygen(const Options& o)
{
    std::string error;
    const rcm::secure::SecretKey key = rcm::secure::generateKey();
    if (!rcm::secure::writeKeyFile(o.file, key, error)) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return kExitFailed;
    }
    std::printf("fingerprint %s\n", rcm::secure::fingerprint(key).c_str());
    return kExitOk;
}

int stationkey(const Options& o)
{
    // One level of a broker topic, as the console names stations there.
    for (const char c : o.station)
        if (c == '/' || c == '+' || c == '#' || static_cast<unsigned char>(c) <= ' ') {
            std::fprintf(stderr, "rcm: the station \"%s\" cannot be named on a broker: no '/', '+', '#' or blanks\n",
                         o.station.c_str());
            return kExitMisuse;
        }
    std::string error;
    struct stat st {};
    if (::stat(o.file.c_str(), &st) == 0) {
        const std::optional<rcm::secure::StationSigningKey> existing =
            rcm::secure::StationSigningKey::fromFile(o.file, error);
        if (!existing) {
            std::fprintf(stderr, "rcm: %s\n", error.c_str());
            return kExitFailed;
        }
        std::fprintf(stderr, "rcm: %s exists already: its trust line, unchanged\n", o.file.c_str());
        std::printf("%s %s\n", o.station.c_str(), rcm::secure::hexOf(existing->publicKey()).c_str());
        return kExitOk;
    }
    const rcm::secure::StationSigningKey key = rcm::secure::StationSigningKey::generate();
    if (!key.writeFile(o.file, error)) {
        std::fprintf(stderr, "rcm: %s\n", error.c_str());
        return kExitFailed;
    }
    std::printf("%s %s\n", o.station.c_str(), rcm::secure::hexOf(key.publicKey()).c_str());
    return kExitOk;
}

}  // namespace rcm::cli
