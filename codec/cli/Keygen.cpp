#include "codec/cli/Keygen.h"

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

}  // namespace rcm::cli
