// SHA-256 (FIPS 180-4), for content keys that must not collide by accident: the validation
// cache names results by the digest of everything that decides them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace tidepool::base {

/// How a Sha256 compresses its blocks; every engine gives the same digest.
enum class Sha256Engine {
    kFastest,   // the CPU's SHA extensions (SHA-NI) when it has them, else kPortable
    kPortable,  // plain C++: the reference the fast path is tested against
};

/// An incremental SHA-256: Update any number of times, then Finish once. Never fails.
class Sha256 {
public:
    explicit Sha256(Sha256Engine engine = Sha256Engine::kFastest);

    /// Whether this CPU has the SHA extensions kFastest uses (x86-64 only).
    static bool HasShaExtensions();

    /// Appends `data` to the message.
    Sha256& Update(std::string_view data);

    /// The digest of everything appended; the object must not be used afterwards.
    std::array<std::uint8_t, 32> Finish();

    /// The digest of everything appended as 64 lowercase hex digits; as Finish.
    std::string FinishHex();

private:
    // Compresses `count` consecutive 64-byte blocks into state_.
    void Compress(const std::uint8_t* blocks, std::size_t count);

    std::array<std::uint32_t, 8> state_;
    bool use_extensions_ = false;
    std::array<std::uint8_t, 64> buffer_{};
    std::size_t buffered_ = 0;
    std::uint64_t length_ = 0;  // bytes appended
};

/// The SHA-256 of `data` as 64 lowercase hex digits.
std::string Sha256Hex(std::string_view data);

}  // namespace tidepool::base
