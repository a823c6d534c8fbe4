#include "tidepool/base/Sha256.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace tidepool::base {
namespace {

// Every vector runs through both engines: kFastest (the SHA extensions on a CPU that has them)
// and kPortable (the reference).
class Sha256Test : public ::testing::TestWithParam<Sha256Engine> {
protected:
    std::string Digest(const std::string& message) const {
        return Sha256(GetParam()).Update(message).FinishHex();
    }
};

INSTANTIATE_TEST_SUITE_P(Engines, Sha256Test,
                         ::testing::Values(Sha256Engine::kFastest, Sha256Engine::kPortable),
                         [](const ::testing::TestParamInfo<Sha256Engine>& engine) {
                             return engine.param == Sha256Engine::kFastest ? "Fastest" : "Portable";
                         });

// FIPS 180-4 / NIST CAVP example digests.
TEST_P(Sha256Test, KnownDigestsOfShortMessages) {
    EXPECT_EQ(Digest(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(Digest("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(Digest("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    // FIPS 180-4's two-block example of 112 bytes.
    EXPECT_EQ(Digest("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                     "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"),
              "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST_P(Sha256Test, MessagesAroundTheBlockAndPaddingBoundaries) {
    // 55 bytes fit one padded block, 56 need two; 64 is exactly one block.
    EXPECT_EQ(Digest(std::string(55, 'a')),
              "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
    EXPECT_EQ(Digest(std::string(56, 'a')),
              "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
    EXPECT_EQ(Digest(std::string(64, 'a')),
              "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

TEST_P(Sha256Test, PiecewiseUpdatesGiveTheDigestOfTheWholeMessage) {
    // One million 'a' (the standard long test vector), in uneven pieces across block borders.
    Sha256 hash(GetParam());
    std::size_t left = 1000000;
    for (std::size_t piece = 1; left > 0; piece = piece % 97 + 1) {
        const std::size_t n = std::min(piece, left);
        hash.Update(std::string(n, 'a'));
        left -= n;
    }
    EXPECT_EQ(hash.FinishHex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_P(Sha256Test, ManyBlocksInOneUpdateGiveTheDigestOfTheWholeMessage) {
    // The same million bytes in one Update: the fast engine compresses them in one call.
    EXPECT_EQ(Digest(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256EngineTest, EnginesAgreeOnEveryLengthUpToFiveBlocks) {
    // Bytes that are not a repeated letter, so a word or byte-order mistake shows.
    std::string message;
    std::uint32_t x = 12345;
    for (int i = 0; i < 320; ++i) {
        x = x * 1103515245U + 12345U;
        message += static_cast<char>(x >> 24);
    }
    for (std::size_t size = 0; size <= message.size(); ++size) {
        const std::string_view prefix(message.data(), size);
        EXPECT_EQ(Sha256(Sha256Engine::kFastest).Update(prefix).FinishHex(),
                  Sha256(Sha256Engine::kPortable).Update(prefix).FinishHex())
                << size << " bytes";
    }
}

TEST(Sha256EngineTest, ShaExtensionsAreDetectedWhenTheCpuListsThem) {
    // /proc/cpuinfo's "sha_ni" flag is the kernel's reading of the same CPUID bit.
    std::FILE* cpuinfo = std::fopen("/proc/cpuinfo", "r");
    if (cpuinfo == nullptr) {
        GTEST_SKIP() << "no /proc/cpuinfo";
    }
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, cpuinfo)) > 0;) {
        text.append(buffer, n);
    }
    std::fclose(cpuinfo);
    EXPECT_EQ(Sha256::HasShaExtensions(), text.find(" sha_ni") != std::string::npos);
}

}  // namespace
}  // namespace tidepool::base
