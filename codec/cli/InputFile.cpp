#include "codec/cli/InputFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace rcm::cli {

bool readAll(const std::string& path, std::vector<std::uint8_t>& out, std::string& error)
{
    std::FILE* f = path.empty() || path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!f) {
        error = "cannot open " + path + ": " + std::strerror(errno);
        return false;
    }
    std::uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        out.insert(out.end(), buf, buf + n);
    const bool failed = std::ferror(f);
    if (f != stdin)
        std::fclose(f);
    if (failed) {
        error = "cannot read " + inputName(path);
        return false;
    }
    return true;
}

std::string inputName(const std::string& path)
{
    return path.empty() || path == "-" ? "<stdin>" : path;
}

}  // namespace rcm::cli
