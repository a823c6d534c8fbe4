// The claim table two forked processes share (base/SharedClaims.h).
#include "tidepool/base/SharedClaims.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace tidepool::base {
namespace {

using namespace std::chrono_literals;
using State = SharedClaims::State;

// Runs `child` in a forked process and waits for it; true when it exited with 0.
template <typename Child>
bool InAForkedProcess(Child child) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        child();
        ::_exit(0);
    }
    int status = 0;
    return pid > 0 && ::waitpid(pid, &status, 0) == pid && WIFEXITED(status) &&
           WEXITSTATUS(status) == 0;
}

// The units the helper has claimed, done or not.
std::size_t HelperUnits(const SharedClaims& claims) {
    std::size_t units = 0;
    for (std::size_t i = 0; i < claims.Size(); ++i) {
        units += claims.HelperHas(i) ? 1U : 0U;
    }
    return units;
}

TEST(SharedClaimsTest, AUnitClaimedInAForkedProcessIsSeenClaimedByTheParent) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(8);
    ASSERT_TRUE(claims);
    ASSERT_TRUE(InAForkedProcess([&] {
        for (std::size_t i = 4; i < 8; ++i) {
            if (!claims->ClaimForHelper(i) || !claims->FinishForHelper(i)) {
                ::_exit(1);
            }
        }
    }));
    for (std::size_t i = 0; i < 8; ++i) {
        EXPECT_EQ(claims->ClaimForOwner(i), i < 4) << i;
        EXPECT_EQ(claims->StateOf(i), i < 4 ? State::kOwner : State::kHelperDone) << i;
    }
    EXPECT_EQ(HelperUnits(*claims), 4U);
    EXPECT_FALSE(claims->HelperHas(8));  // past the table
}

TEST(SharedClaimsTest, OwnerAndHelperRacingForEveryUnitEachGetEveryUnitOnceBetweenThem) {
    constexpr std::size_t kUnits = 20000;
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(kUnits);
    ASSERT_TRUE(claims);
    std::size_t owner = 0;
    const pid_t pid = ::fork();
    if (pid == 0) {
        // The helper takes from the end, as the second process does.
        for (std::size_t i = kUnits; i-- > 0;) {
            if (claims->ClaimForHelper(i)) {
                claims->FinishForHelper(i);
            }
        }
        ::_exit(0);
    }
    ASSERT_GT(pid, 0);
    for (std::size_t i = 0; i < kUnits; ++i) {
        owner += claims->ClaimForOwner(i) ? 1U : 0U;
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_EQ(owner + HelperUnits(*claims), kUnits);
    for (std::size_t i = 0; i < kUnits; ++i) {
        const State state = claims->StateOf(i);
        ASSERT_TRUE(state == State::kOwner || state == State::kHelperDone) << i;
    }
}

TEST(SharedClaimsTest, TheOwnerMayClaimItsOwnUnitAgainButNotTheHelpers) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(2);
    ASSERT_TRUE(claims);
    EXPECT_TRUE(claims->ClaimForOwner(0));
    EXPECT_TRUE(claims->ClaimForOwner(0));
    EXPECT_FALSE(claims->ClaimForHelper(0));
    EXPECT_TRUE(claims->ClaimForHelper(1));
    EXPECT_FALSE(claims->ClaimForHelper(1));
    EXPECT_FALSE(claims->ClaimForOwner(1));
}

TEST(SharedClaimsTest, AwaitingAHelperThatFinishesReturnsNothingToRedo) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(3);
    ASSERT_TRUE(claims);
    ASSERT_TRUE(claims->ClaimForHelper(2));
    // The helper finishes only after the owner has polled twice (a byte down the pipe at each
    // poll), so the count below does not depend on how the two processes are scheduled.
    int told[2];
    ASSERT_EQ(::pipe(told), 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(told[1]);
        char polled[2];
        std::size_t got = 0;
        while (got < sizeof polled) {
            const ssize_t n = ::read(told[0], polled + got, sizeof polled - got);
            if (n <= 0) {
                ::_exit(1);  // the owner closed the pipe early: it failed already
            }
            got += static_cast<std::size_t>(n);
        }
        claims->FinishForHelper(2);
        ::_exit(0);
    }
    ASSERT_GT(pid, 0);
    ::close(told[0]);
    int polls = 0;  // the owner's progress line is told at each poll while it waits
    const std::vector<std::size_t> redo = claims->AwaitHelper(20s, 5ms, [&] {
        if (++polls <= 2) {
            const char byte = 'p';
            EXPECT_EQ(::write(told[1], &byte, 1), 1);
        }
    });
    ::close(told[1]);
    EXPECT_TRUE(redo.empty());
    EXPECT_EQ(claims->StateOf(2), State::kHelperDone);
    EXPECT_GE(polls, 2);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(SharedClaimsTest, AStalledHelpersUnfinishedUnitsAreTakenBackAndItsLateFinishIsRefused) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(4);
    ASSERT_TRUE(claims);
    ASSERT_TRUE(claims->ClaimForHelper(1));
    ASSERT_TRUE(claims->FinishForHelper(1));
    ASSERT_TRUE(claims->ClaimForHelper(3));  // and then it stops beating
    const std::vector<std::size_t> taken = claims->AwaitHelper(50ms, 5ms);
    EXPECT_EQ(taken, std::vector<std::size_t>{3});
    EXPECT_EQ(claims->StateOf(3), State::kOwner);
    EXPECT_EQ(claims->StateOf(1), State::kHelperDone);  // finished work is kept
    EXPECT_FALSE(claims->FinishForHelper(3));
    EXPECT_EQ(claims->StateOf(3), State::kOwner);
}

TEST(SharedClaimsTest, TheHelperSaysWhetherItIsTakingUnits) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(1);
    ASSERT_TRUE(claims);
    EXPECT_FALSE(claims->HelperTaking());
    EXPECT_FALSE(claims->HelperStopped());  // not yet started is not stopped
    ASSERT_TRUE(InAForkedProcess([&] { claims->SetHelperTaking(true); }));
    EXPECT_TRUE(claims->HelperTaking());
    EXPECT_FALSE(claims->HelperStopped());
    ASSERT_TRUE(InAForkedProcess([&] { claims->SetHelperTaking(false); }));
    EXPECT_FALSE(claims->HelperTaking());
    EXPECT_TRUE(claims->HelperStopped());
}

TEST(SharedClaimsTest, AHelperIsSilentWhenItsLastBeatIsOlderThanAsked) {
    using namespace std::chrono_literals;
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(1);
    ASSERT_TRUE(claims);
    std::this_thread::sleep_for(30ms);
    EXPECT_TRUE(claims->HelperSilentFor(10ms));
    EXPECT_FALSE(claims->HelperSilentFor(60s));
    ASSERT_TRUE(InAForkedProcess([&] { claims->Beat(); }));  // a beat from another process
    EXPECT_FALSE(claims->HelperSilentFor(10s));
}

TEST(SharedClaimsTest, TheHelpersForecastOfWhenItStartsTakingUnitsReachesTheOwner) {
    const std::unique_ptr<SharedClaims> claims = SharedClaims::Create(1);
    ASSERT_TRUE(claims);
    EXPECT_FALSE(claims->HelperExpectedAt());  // nothing said yet
    const std::chrono::steady_clock::time_point when =
            std::chrono::steady_clock::now() + std::chrono::seconds(42);
    ASSERT_TRUE(InAForkedProcess([&] { claims->ExpectHelperAt(when); }));
    ASSERT_TRUE(claims->HelperExpectedAt());
    EXPECT_EQ(*claims->HelperExpectedAt(), when);
}

}  // namespace
}  // namespace tidepool::base
