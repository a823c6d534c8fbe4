#include "tidepool/pipeline/RunRecordCache.h"

#include "tidepool/base/Sha256.h"

#include <cerrno>
#include <charconv>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tidepool::pipeline {
namespace {

// The first line of every record; a change of the layout below changes it.
constexpr std::string_view kRecordTag = "tidepool run record 1\n";

// The SHA-256 of `path`'s bytes and its status, or none when it cannot be read whole.
std::optional<std::string> FileDigest(const std::filesystem::path& path, struct stat* info) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        return std::nullopt;
    }
    bool ok = ::fstat(fd, info) == 0 && S_ISREG(info->st_mode);
    base::Sha256 digest;
    char buffer[16384];
    while (ok) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        ok = n >= 0;
        if (n <= 0) {
            break;
        }
        digest.Update(std::string_view(buffer, static_cast<std::size_t>(n)));
    }
    ::close(fd);
    return ok ? std::optional<std::string>(digest.FinishHex()) : std::nullopt;
}

bool NotBefore(const timespec& time, const timespec& reference) {
    return time.tv_sec > reference.tv_sec ||
           (time.tv_sec == reference.tv_sec && time.tv_nsec >= reference.tv_nsec);
}

// "name <length>\n<bytes>\n", or "name -\n" for none.
void PutField(std::string* text, std::string_view name, const std::optional<std::string>& value) {
    *text += name;
    if (!value) {
        *text += " -\n";
        return;
    }
    *text += ' ';
    *text += std::to_string(value->size());
    *text += '\n';
    *text += *value;
    *text += '\n';
}

// Reads what PutField wrote off the front of `text`; false when it is not there whole.
bool TakeField(std::string_view* text, std::string_view name, std::optional<std::string>* value) {
    const std::size_t end = text->find('\n');
    if (end == std::string_view::npos || text->substr(0, name.size()) != name ||
        end <= name.size() + 1 || (*text)[name.size()] != ' ') {
        return false;
    }
    const std::string_view size_text = text->substr(name.size() + 1, end - name.size() - 1);
    text->remove_prefix(end + 1);
    if (size_text == "-") {
        value->reset();
        return true;
    }
    std::size_t size = 0;
    const char* size_end = size_text.data() + size_text.size();
    if (std::from_chars(size_text.data(), size_end, size).ptr != size_end || text->size() <= size ||
        (*text)[size] != '\n') {
        return false;
    }
    *value = std::string(text->substr(0, size));
    text->remove_prefix(size + 1);
    return true;
}

// As TakeField, for a field that is always present.
bool TakeText(std::string_view* text, std::string_view name, std::string* value) {
    std::optional<std::string> field;
    if (!TakeField(text, name, &field) || !field) {
        return false;
    }
    *value = std::move(*field);
    return true;
}

}  // namespace

bool RunRecord::operator==(const RunRecord& other) const {
    return out == other.out && err == other.err && exit_code == other.exit_code &&
           manifest == other.manifest && depfile == other.depfile &&
           report_file == other.report_file;
}

RunRecordCache::RunRecordCache(base::ContentCache& cache, const std::string& key_text)
    : cache_(cache), key_(base::Sha256().Update("run record\n").Update(key_text).FinishHex()) {}

timespec RunRecordCache::StartTime() {
    timespec now{};
    ::clock_gettime(CLOCK_REALTIME_COARSE, &now);
    return now;
}

std::optional<RunRecord> RunRecordCache::Find() {
    const std::optional<std::string> payload = cache_.Load(key_);
    if (!payload) {
        return std::nullopt;
    }
    std::optional<std::pair<std::vector<ReadFileDigest>, RunRecord>> entry = Decode(*payload);
    if (!entry) {
        return std::nullopt;
    }
    for (const ReadFileDigest& file : entry->first) {
        struct stat info {};
        if (FileDigest(file.path, &info) != file.sha256) {
            return std::nullopt;
        }
    }
    return std::move(entry->second);
}

bool RunRecordCache::Keep(const std::vector<std::filesystem::path>& files_read,
                          const timespec& started, const RunRecord& record) {
    std::vector<ReadFileDigest> files;
    for (const std::filesystem::path& path : files_read) {
        struct stat info {};
        std::optional<std::string> digest = FileDigest(path, &info);
        if (!digest || NotBefore(info.st_mtim, started) || NotBefore(info.st_ctim, started)) {
            return false;
        }
        files.push_back({path.string(), std::move(*digest)});
    }
    cache_.Store(key_, Encode(files, record));
    return true;
}

std::string RunRecordCache::Encode(const std::vector<ReadFileDigest>& files,
                                   const RunRecord& record) {
    std::string text(kRecordTag);
    text += "files " + std::to_string(files.size()) + "\n";
    for (const ReadFileDigest& file : files) {
        PutField(&text, file.sha256, file.path);
    }
    text += "exit " + std::to_string(record.exit_code) + "\n";
    PutField(&text, "out", record.out);
    PutField(&text, "err", record.err);
    PutField(&text, "manifest", record.manifest);
    PutField(&text, "depfile", record.depfile);
    PutField(&text, "report", record.report_file);
    return text;
}

std::optional<std::pair<std::vector<ReadFileDigest>, RunRecord>> RunRecordCache::Decode(
        std::string_view text) {
    if (text.substr(0, kRecordTag.size()) != kRecordTag) {
        return std::nullopt;
    }
    text.remove_prefix(kRecordTag.size());
    // A whole number ending its line, after "name ".
    auto take_number = [&text](std::string_view name, auto* value) {
        const std::size_t end = text.find('\n');
        if (end == std::string_view::npos || end <= name.size() ||
            text.substr(0, name.size()) != name) {
            return false;
        }
        const char* first = text.data() + name.size();
        const char* last = text.data() + end;
        const bool ok = std::from_chars(first, last, *value).ptr == last;
        text.remove_prefix(end + 1);
        return ok;
    };
    std::size_t count = 0;
    if (!take_number("files ", &count) || count > text.size()) {
        return std::nullopt;
    }
    std::vector<ReadFileDigest> files(count);
    for (ReadFileDigest& file : files) {
        // The digest names the field: 64 hex digits, then the path's length.
        file.sha256 = std::string(text.substr(0, 64));
        if (file.sha256.size() != 64 || !TakeText(&text, file.sha256, &file.path)) {
            return std::nullopt;
        }
    }
    RunRecord record;
    if (!take_number("exit ", &record.exit_code) || !TakeText(&text, "out", &record.out) ||
        !TakeText(&text, "err", &record.err) || !TakeField(&text, "manifest", &record.manifest) ||
        !TakeField(&text, "depfile", &record.depfile) ||
        !TakeField(&text, "report", &record.report_file) || !text.empty()) {
        return std::nullopt;
    }
    return std::make_pair(std::move(files), std::move(record));
}

}  // namespace tidepool::pipeline
