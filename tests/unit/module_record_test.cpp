// The daemon's restart guard before it is ready (module_record.hpp, StartRecord): each start is
// noted in the store until the daemon is ready; after kFailedStartsForSafeStart noted starts
// within kFailedStartWindow the next start runs sim without trying any driver module.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "daemon/module_record.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using Clock = StartRecord::Clock;

const Clock::time_point kT0 = Clock::time_point(std::chrono::seconds(1'800'000'000));

// `count` starts that never became ready, at `t`, t + 1 s, ...
void fail_starts(const std::filesystem::path& file, int count, Clock::time_point t) {
    for (int i = 0; i < count; ++i) {
        StartRecord start(file, t + std::chrono::seconds(i));
    }
}

TEST(StartRecord, TheStartAfterTwoFailedOnesIsOrdinaryAndTheOneAfterThreeIsSafe) {
    testing::TempDir store;
    const auto file = store.path() / kStartRecordFile;
    fail_starts(file, kFailedStartsForSafeStart - 1, kT0);
    {
        StartRecord start(file, kT0 + std::chrono::seconds(10));
        EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart - 1);
        EXPECT_EQ(start.safe_start_reason(), "") << "the last start allowed to try modules";
    }
    StartRecord start(file, kT0 + std::chrono::seconds(11));
    EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart);
    EXPECT_EQ(start.safe_start_reason(),
              "vibscored's last 3 starts ended before it was ready (" + file.string() +
                  ", the first 11 s ago): starting with driver sim and without trying any "
                  "driver module, so that the daemon serves; a reload (SIGHUP, systemctl "
                  "reload vibscored) tries the configuration again");
}

TEST(StartRecord, AStartThatBecameReadyClearsTheCount) {
    testing::TempDir store;
    const auto file = store.path() / kStartRecordFile;
    fail_starts(file, kFailedStartsForSafeStart - 1, kT0);
    {
        StartRecord start(file, kT0 + std::chrono::seconds(5));
        start.ready();
    }
    EXPECT_FALSE(std::filesystem::exists(file));
    fail_starts(file, kFailedStartsForSafeStart - 1, kT0 + std::chrono::seconds(6));
    StartRecord start(file, kT0 + std::chrono::seconds(20));
    EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart - 1);
    EXPECT_EQ(start.safe_start_reason(), "");
}

TEST(StartRecord, OnlyFailedStartsWithinTheWindowCount) {
    testing::TempDir store;
    const auto file = store.path() / kStartRecordFile;
    fail_starts(file, kFailedStartsForSafeStart, kT0);
    // The first of them leaves the window at kT0 + window: the last moment it counts is 1 s
    // before.
    {
        StartRecord start(file, kT0 + kFailedStartWindow - std::chrono::seconds(1));
        EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart);
        EXPECT_THAT(start.safe_start_reason(), HasSubstr("starting with driver sim"));
    }
    std::filesystem::remove(file);
    fail_starts(file, kFailedStartsForSafeStart, kT0);
    StartRecord start(file, kT0 + kFailedStartWindow);
    EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart - 1);
    EXPECT_EQ(start.safe_start_reason(), "");
}

TEST(StartRecord, ASafeStartThatFailsTooKeepsTheNextOneSafe) {
    testing::TempDir store;
    const auto file = store.path() / kStartRecordFile;
    fail_starts(file, kFailedStartsForSafeStart + 1, kT0);
    StartRecord start(file, kT0 + std::chrono::seconds(30));
    EXPECT_EQ(start.failed_starts(), kFailedStartsForSafeStart + 1);
    EXPECT_NE(start.safe_start_reason(), "");
}

TEST(StartRecord, NoFileKeepsNoRecordAndAnUnwritableStoreOnlyWarns) {
    StartRecord none("", kT0);
    EXPECT_EQ(none.failed_starts(), 0);
    none.ready();
    ::testing::internal::CaptureStderr();
    StartRecord missing("/nonexistent/store/.starts", kT0);
    EXPECT_THAT(::testing::internal::GetCapturedStderr(),
                HasSubstr("cannot note this start in /nonexistent/store/.starts"));
    EXPECT_EQ(missing.safe_start_reason(), "");
}

}  // namespace
}  // namespace vibscore::daemon
