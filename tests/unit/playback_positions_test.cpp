#include <gtest/gtest.h>

#include <string>

#include "daemon/playback_positions.hpp"

namespace vibscore::daemon {
namespace {

constexpr std::uint64_t kT0 = 7'000'000;  // the injected clock's start

TEST(PositionBudget, AConnectionHasABurstOfTwoThenOneEvery20Ms) {
    PositionBudget budget;
    EXPECT_TRUE(budget.take(":1.7", kT0));
    EXPECT_TRUE(budget.take(":1.7", kT0));
    EXPECT_FALSE(budget.take(":1.7", kT0)) << "the burst is spent";
    EXPECT_EQ(budget.available_at(":1.7", kT0), kT0 + 20'000);
    EXPECT_FALSE(budget.take(":1.7", kT0 + 19'999)) << "the last microsecond refused";
    EXPECT_TRUE(budget.take(":1.7", kT0 + 20'000)) << "the first allowed";
    EXPECT_FALSE(budget.take(":1.7", kT0 + 20'000));
}

TEST(PositionBudget, AConnectionTryingAtEveryMillisecondGetsAtMost50ASecondAndItsBurst) {
    PositionBudget budget;
    int reported = 0;
    for (std::uint64_t t = 0; t < 10'000'000; t += 1'000) {
        reported += budget.take(":1.7", kT0 + t) ? 1 : 0;
    }
    // The burst, then one each time 20 ms of credit are back: 2 + 499 in 10 s.
    EXPECT_EQ(reported, 501);
    EXPECT_LE(reported, 50 * 10 + 2);
}

TEST(PositionBudget, ARefusedTrySpendsNothing) {
    PositionBudget budget;
    budget.take(":1.7", kT0);
    budget.take(":1.7", kT0);
    for (std::uint64_t t = 0; t < 20'000; t += 100) {
        EXPECT_FALSE(budget.take(":1.7", kT0 + t));
    }
    EXPECT_TRUE(budget.take(":1.7", kT0 + 20'000));
}

TEST(PositionBudget, TheBusWideTotalBoundsManyConnectionsTogether) {
    PositionBudget budget;
    int reported = 0;
    // Ten connections, each asking at every millisecond: 100 a second in all, and the burst.
    for (std::uint64_t t = 0; t < 10'000'000; t += 1'000) {
        reported += budget.take(":1." + std::to_string(t / 1'000 % 10), kT0 + t) ? 1 : 0;
    }
    // The total's burst, then one each time 10 ms of credit are back: 4 + 999 in 10 s.
    EXPECT_EQ(reported, 1003);
    EXPECT_LE(reported, 100 * 10 + 4);
}

TEST(PositionBudget, TheTotalsLastRefusedAndFirstAllowedMoment) {
    PositionBudget budget;
    for (const char* sender : {":1.1", ":1.2"}) {
        EXPECT_TRUE(budget.take(sender, kT0));
        EXPECT_TRUE(budget.take(sender, kT0));
    }
    EXPECT_FALSE(budget.take(":1.3", kT0)) << "a fresh connection, but the total's burst is spent";
    EXPECT_EQ(budget.available_at(":1.3", kT0), kT0 + 10'000);
    EXPECT_FALSE(budget.take(":1.3", kT0 + 9'999));
    EXPECT_TRUE(budget.take(":1.3", kT0 + 10'000));
}

TEST(PositionBudget, AConnectionWhoseBudgetIsFullAgainIsForgotten) {
    PositionBudget budget;
    budget.take(":1.1", kT0);
    budget.take(":1.2", kT0 + 19'999);
    EXPECT_EQ(budget.remembered(), 2u) << ":1.1 is a microsecond short of full";
    budget.take(":1.3", kT0 + 20'000);
    EXPECT_EQ(budget.remembered(), 2u) << ":1.1 full again, so forgotten; :1.2 is not";
}

}  // namespace
}  // namespace vibscore::daemon
