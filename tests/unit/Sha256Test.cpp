#include "tidepool/base/Sha256.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace tidepool::base {
namespace {

// FIPS 180-4 / NIST CAVP example digests.
TEST(Sha256Test, KnownDigestsOfShortMessages) {
    EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256Test, MessagesAroundTheBlockAndPaddingBoundaries) {
    // 55 bytes fit one padded block, 56 need two; 64 is exactly one block.
    EXPECT_EQ(Sha256Hex(std::string(55, 'a')),
              "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
    EXPECT_EQ(Sha256Hex(std::string(56, 'a')),
              "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
    EXPECT_EQ(Sha256Hex(std::string(64, 'a')),
              "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

TEST(Sha256Test, PiecewiseUpdatesGiveTheDigestOfTheWholeMessage) {
    // One million 'a' (the standard long test vector), in uneven pieces across block borders.
    Sha256 hash;
    std::size_t left = 1000000;
    for (std::size_t piece = 1; left > 0; piece = piece % 97 + 1) {
        const std::size_t n = std::min(piece, left);
        hash.Update(std::string(n, 'a'));
        left -= n;
    }
    EXPECT_EQ(hash.FinishHex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

}  // namespace
}  // namespace tidepool::base
