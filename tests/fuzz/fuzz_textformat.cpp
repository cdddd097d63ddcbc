// Random and mutated text through the parser, and random bytes through the
// block decoders, under ASan/UBSan: nothing may crash, hang or read out of
// bounds. Fixed seed, bounded work: a CTest target, not an open-ended fuzzer.
#include "tests/support/RandomMessage.h"

#include "codec/message/MessageDecoder.h"
#include "codec/message/MessageEncoder.h"
#include "codec/message/TextFormat.h"

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

using namespace rcm;

namespace {

std::string mutate(std::mt19937_64& rng, std::string s)
{
    static const char* const pieces[] = {" ", "\n", "#", "\"", "\\x", "=", "_", "0x", "-", ".", "BEGIN ", "END\n",
                                         "BEGIN engine\n", "99999999999999999999", "\t", ":", "\r\n", "\\"};
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits && !s.empty(); ++e) {
        const std::size_t at = rng() % s.size();
        switch (rng() % 4) {
        case 0: s.erase(at, 1 + rng() % 6); break;
        case 1: s.insert(at, pieces[rng() % std::size(pieces)]); break;
        case 2: s[at] = static_cast<char>(rng() % 256); break;
        default: s.insert(at, s.substr(rng() % s.size(), rng() % 40)); break;
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    // A round: one mutated text, one of random bytes, two random block pairs.
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 100000;
    std::mt19937_64 rng(0xF022);
    std::size_t parsedOk = 0, blocksRead = 0;
    for (int i = 0; i < rounds; ++i) {
        const std::string text = mutate(rng, formatMessage(test::randomMessage(rng)));
        const ParseResult r = parseMessage(text);
        if (r.ok()) {
            ++parsedOk;
            Diagnostics errors;
            (void)encodeFrame(r.message, errors);
        }
        std::string junk(rng() % 300, '\0');
        for (char& c : junk)
            c = static_cast<char>(rng() % 256);
        (void)parseMessage(junk);
        for (int k = 0; k < 2; ++k) {
            DecodedBlocks blocks;
            for (auto* b : {&blocks.block1, &blocks.block2}) {
                // Half the time mostly padding, so items deep in the block are reached.
                const bool sparse = rng() % 2;
                for (auto& x : *b)
                    x = sparse && rng() % 4 ? 0x55 : static_cast<std::uint8_t>(rng());
            }
            const DecodeResult d = decodeBlocks(blocks);
            blocksRead += d.diagnostics.size();
            (void)formatMessage(d.message);
        }
    }
    std::printf("fuzz_textformat: %d rounds, %zu mutated texts parsed, %zu block diagnostics; no crash\n", rounds,
                parsedOk, blocksRead);
    return 0;
}
