#include "tidepool/AtomicFile.h"

#include <cstdio>
#include <fstream>
#include <system_error>

#include <unistd.h>

#include <fmt/format.h>

namespace tidepool {

std::string WriteFileAtomically(const std::filesystem::path& path, std::string_view content) {
    std::error_code ec;
    if (path.has_parent_path()) {
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) {
            return fmt::format("{}: cannot create folder: {}", path.parent_path().string(),
                               ec.message());
        }
    }
    // Same folder as the destination, so the rename never crosses a file system.
    const std::filesystem::path temp =
            path.parent_path() / fmt::format(".{}.tmp.{}", path.filename().string(), ::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) {
            return fmt::format("{}: cannot write: {}", temp.string(),
                               std::error_code(errno, std::generic_category()).message());
        }
        out.write(content.data(), static_cast<std::streamsize>(content.size()));
        out.flush();
        if (!out) {
            out.close();
            std::filesystem::remove(temp, ec);
            return fmt::format("{}: write failed (disk full?)", path.string());
        }
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        return fmt::format("{}: cannot replace: {}", path.string(), ec.message());
    }
    return {};
}

}  // namespace tidepool
