#include "tidepool/base/FileKind.h"

#include <system_error>

namespace tidepool::base {

std::string WhyNotARegularFile(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec && ec != std::errc::no_such_file_or_directory) {
        return ec.message();
    }
    switch (status.type()) {
        case std::filesystem::file_type::regular:
            return "";
        case std::filesystem::file_type::not_found:
            return "no such file";
        case std::filesystem::file_type::directory:
            return "is a folder, not a file";
        default:
            return "is a device, a named pipe or a socket, not a regular file";
    }
}

}  // namespace tidepool::base
