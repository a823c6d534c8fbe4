#include "tidepool/base/CacheBundle.h"

#include <charconv>
#include <map>
#include <utility>

namespace tidepool::base {

CacheBundle::CacheBundle(ContentCache& cache, std::string bundle_key, std::string lineage_key)
    : cache_(cache), bundle_key_(std::move(bundle_key)), lineage_key_(std::move(lineage_key)) {
    std::optional<std::string> text = cache_.Load(bundle_key_);
    read_is_current_ = text.has_value();
    if (!text) {
        if (const std::optional<std::string> latest = cache_.Load(lineage_key_)) {
            text = cache_.Load(*latest);
        }
    }
    if (text) {
        if (auto entries = Decode(*text)) {
            read_ = std::move(*entries);
        } else {
            read_is_current_ = false;  // the checksum held but the layout did not: rewrite it
        }
    }
}

std::optional<std::string> CacheBundle::Load(const std::string& key) {
    const auto it = read_.find(key);
    if (it == read_.end()) {
        changed_ = true;
        return std::nullopt;
    }
    used_[key] = it->second;
    return it->second;
}

void CacheBundle::Store(const std::string& key, std::string payload) {
    changed_ = true;
    used_[key] = std::move(payload);
}

void CacheBundle::Save() {
    if (read_is_current_ && !changed_) {
        return;
    }
    cache_.Store(bundle_key_, Encode(used_));
    cache_.Store(lineage_key_, bundle_key_);
}

std::string CacheBundle::Encode(const std::unordered_map<std::string, std::string>& entries) {
    // In key order, so that one set of results always gives the same bytes.
    const std::map<std::string, std::string> sorted(entries.begin(), entries.end());
    std::string text;
    for (const auto& [key, payload] : sorted) {
        text += key;
        text += ' ';
        text += std::to_string(payload.size());
        text += '\n';
        text += payload;
    }
    return text;
}

std::optional<std::unordered_map<std::string, std::string>> CacheBundle::Decode(
        const std::string& text) {
    std::unordered_map<std::string, std::string> entries;
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t space = text.find(' ', at);
        const std::size_t newline = text.find('\n', at);
        if (space == std::string::npos || newline == std::string::npos || space > newline ||
            space == at) {
            return std::nullopt;
        }
        std::size_t size = 0;
        const char* first = text.data() + space + 1;
        const char* last = text.data() + newline;
        const auto parsed = std::from_chars(first, last, size);
        if (parsed.ec != std::errc() || parsed.ptr != last || size > text.size() - newline - 1) {
            return std::nullopt;
        }
        entries[text.substr(at, space - at)] = text.substr(newline + 1, size);
        at = newline + 1 + size;
    }
    return entries;
}

}  // namespace tidepool::base
