// A whole input file, or standard input, read into memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rcm::cli {

// Reads all of `path` (standard input for "" and "-") into `out`; false with
// the reason in `error` when it cannot.
bool readAll(const std::string& path, std::vector<std::uint8_t>& out, std::string& error);

// How messages name the input: the path, or <stdin>.
std::string inputName(const std::string& path);

}  // namespace rcm::cli
