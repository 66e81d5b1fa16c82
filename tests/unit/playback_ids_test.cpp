#include "daemon/playback_ids.hpp"

#include <gtest/gtest.h>

#include <chrono>

#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

constexpr std::uint64_t kRun = std::uint64_t{1} << 32;

TEST(PlaybackIds, EachRunStartsAboveEveryIdOfTheRunsBefore) {
    const vibscore::testing::TempDir store;
    EXPECT_EQ(first_playback_id(store.path()), 1 * kRun + 1);
    EXPECT_EQ(first_playback_id(store.path()), 2 * kRun + 1);
    EXPECT_EQ(vibscore::testing::read_file(store.path() / kRunCounterFile), "2\n");
}

TEST(PlaybackIds, AnUnreadableCountStartsOver) {
    const vibscore::testing::TempDir store;
    store.write(kRunCounterFile, "many\n");
    EXPECT_EQ(first_playback_id(store.path()), 1 * kRun + 1);
}

TEST(PlaybackIds, AStoreThatCannotKeepTheCountNumbersTheRunByTheRealtimeClock) {
    const vibscore::testing::TempDir dir;
    const auto not_a_directory = dir.write("file", "");
    const auto now =
        static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                       std::chrono::system_clock::now().time_since_epoch())
                                       .count());
    const auto id = first_playback_id(not_a_directory / "store");
    EXPECT_EQ(id & 0xffffffffu, 1u);
    EXPECT_GE(id >> 32, now & 0xffffffffu);
    EXPECT_LE(id >> 32, (now + 60) & 0xffffffffu);
}

}  // namespace
}  // namespace vibscore::daemon
