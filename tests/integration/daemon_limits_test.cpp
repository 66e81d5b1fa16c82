// Issue 33, rows 2 and 3: no caller holds the vibrator. The real vibscored on a private bus with
// short [limits], so the edges the unit tests pin (playback_limits_test.cpp) are seen end to end.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

#include "tests/support/daemon_fixture.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using testing::SeenSignal;
using ::testing::StartsWith;
using Clock = std::chrono::steady_clock;

constexpr uid_t kNobody = 65534;
constexpr const char* kCoolingDown = "org.vibscore.Haptics1.Error.CoolingDown";

std::map<std::string, sdbus::Variant> options(const std::string& usage, int repeat) {
    return {{"usage", sdbus::Variant(usage)}, {"repeat", sdbus::Variant(repeat)}};
}

std::string error_name_of(const std::function<void()>& call) {
    try {
        call();
    } catch (const sdbus::Error& error) {
        return error.getName() + ": " + error.getMessage();
    }
    return "<no error>";
}

class DaemonLimits : public ::testing::Test {
  protected:
    DaemonFixture daemon{"[limits]\nmax-on-time = 0.5\ncool-down = 1\n"};
};

TEST_F(DaemonLimits, ARepeatingNotificationEndsAtItsMaximumOnTimeAndItsUserCoolsDown) {
    auto holder = daemon.client();
    const auto before = Clock::now();
    const auto id = holder->Play("ringtone", options("notification", -1));
    // Arbitration is as it was: meanwhile another user's notification one-shot is Busy.
    const auto busy =
        daemon.call({"Play", "sa{sv}", "touch-tick", "1", "usage", "s", "notification"}, kNobody);
    EXPECT_THAT(busy.err, HasSubstr("repeating notification playback is in progress"));
    std::string reason;
    ASSERT_TRUE(holder->wait_finished(id, &reason, std::chrono::seconds(5)));
    EXPECT_GE(Clock::now() - before, std::chrono::milliseconds(500)) << "not before the limit";
    EXPECT_EQ(reason,
              "limit-exceeded: played for its maximum on-time of 0.5 s ([limits] max-on-time)");

    // Re-taking the actuator with a repeating playback at once is refused, by name...
    EXPECT_THAT(error_name_of([&] { holder->Play("ringtone", options("notification", -1)); }),
                StartsWith(std::string(kCoolingDown) + ": uid "));
    EXPECT_THAT(error_name_of([&] { holder->Play("ringtone", options("touch", 2)); }),
                StartsWith(kCoolingDown));
    // ...a one-shot is not, nor is another user.
    EXPECT_EQ(error_name_of([&] { holder->Play("touch-tick", options("touch", 0)); }),
              "<no error>");
    const auto other = daemon.call(
        {"Play", "sa{sv}", "touch-tick", "2", "usage", "s", "touch", "repeat", "i", "1"}, kNobody);
    EXPECT_EQ(other.exit_code, 0) << other.err;

    // Once the cool-down has passed, the same request is allowed (tried at each of the
    // fixture's polls, on the one signal that names the ended playback).
    std::string last;
    std::uint64_t again = 0;
    ASSERT_TRUE(holder->wait_for(
        [&](const SeenSignal& seen) {
            if (seen.name != "PlaybackStarted" || seen.id != id) {
                return false;
            }
            last = error_name_of([&] { again = holder->Play("touch-tick", options("touch", 1)); });
            return last == "<no error>";
        },
        std::chrono::seconds(5)))
        << last;
    EXPECT_GE(Clock::now() - before, std::chrono::milliseconds(1500))
        << "0.5 s of playing and 1 s of cool-down";
    EXPECT_NE(again, 0u);
}

// Row 3: a fire-and-forget one-shot (its caller gone at once) is bounded like any other.
TEST_F(DaemonLimits, AFireAndForgetOneShotEndsAtItsMaximumOnTime) {
    auto watcher = daemon.client();
    const auto played =
        daemon.call({"Play", "sa{sv}", "greensleeves", "1", "usage", "s", "media"}, kNobody);
    ASSERT_EQ(played.exit_code, 0) << played.err;
    EXPECT_TRUE(watcher->wait_for(
        [](const SeenSignal& seen) {
            return seen.name == "PlaybackFinished" &&
                   seen.text.starts_with("limit-exceeded: played for its maximum on-time");
        },
        std::chrono::seconds(5)));
}

TEST_F(DaemonLimits, AnAlarmIsNotLimitedAndStopsOnlyWhenStopped) {
    auto root = daemon.client();
    const auto id = root->Play("ringtone", options("alarm", -1));
    EXPECT_FALSE(root->wait_finished(id, nullptr, std::chrono::seconds(2)))
        << "four times the limit of the other usages";
    root->Stop(id);
    std::string reason;
    ASSERT_TRUE(root->wait_finished(id, &reason));
    EXPECT_EQ(reason, "stopped");
}

class DaemonStopAllCoolDown : public ::testing::Test {
  protected:
    DaemonFixture daemon{"[limits]\ncool-down = 1\n"};
};

TEST_F(DaemonStopAllCoolDown, AUserWhosePlaybackAnAdminStoppedMayNotRepeatAtOnce) {
    auto root = daemon.client();
    // Two more times: it ends by itself, so it plays on after busctl left.
    const auto started = daemon.call(
        {"Play", "sa{sv}", "ringtone", "2", "usage", "s", "notification", "repeat", "i", "2"},
        kNobody);
    ASSERT_EQ(started.exit_code, 0) << started.err;
    ASSERT_TRUE(
        root->wait_for([](const SeenSignal& seen) { return seen.name == "PlaybackStarted"; }));
    root->StopAll();
    const auto again = daemon.call(
        {"Play", "sa{sv}", "ringtone", "2", "usage", "s", "notification", "repeat", "i", "2"},
        kNobody);
    EXPECT_NE(again.exit_code, 0);
    EXPECT_THAT(again.err, HasSubstr("([limits] cool-down = 1 s)"));
    const auto one_shot =
        daemon.call({"Play", "sa{sv}", "touch-tick", "1", "usage", "s", "notification"}, kNobody);
    EXPECT_EQ(one_shot.exit_code, 0) << one_shot.err;
    EXPECT_EQ(error_name_of([&] { root->Play("ringtone", options("notification", 1)); }),
              "<no error>")
        << "the admin's own playback did not end";
}

// Row 4: a stream of short Plays, each preempting the one before, gave 111 positions a second;
// now one connection's playbacks together send at most 50 a second (and a burst of 2), and all
// connections together at most 100 (and 4).
class DaemonPositions : public ::testing::Test {
  protected:
    DaemonFixture daemon;

    // Plays short playbacks for a second, each client in turn, as fast as the calls return;
    // returns the seconds from the first Play to the last one's PlaybackFinished, as `watcher`
    // saw it.
    double stream(std::vector<std::unique_ptr<testing::HapticsClient>>& players,
                  testing::HapticsClient& watcher,
                  std::map<std::uint64_t, std::size_t>& player_of) {
        const auto start = Clock::now();
        std::uint64_t last = 0;
        for (std::size_t i = 0; Clock::now() - start < std::chrono::seconds(1); ++i) {
            const auto who = i % players.size();
            last = players[who]->Play("touch-tick", options("touch", 0));
            player_of[last] = who;
        }
        EXPECT_TRUE(watcher.wait_finished(last));
        return std::chrono::duration<double>(Clock::now() - start).count();
    }
};

TEST_F(DaemonPositions, AStreamOfShortPlaysGetsAtMost50PositionsASecond) {
    auto watcher = daemon.client();
    std::vector<std::unique_ptr<testing::HapticsClient>> players;
    players.push_back(daemon.client());
    std::map<std::uint64_t, std::size_t> player_of;
    const double elapsed_s = stream(players, *watcher, player_of);
    std::size_t positions = 0;
    for (const auto& seen : watcher->signals()) {
        positions += seen.name == "PlaybackPosition" ? 1 : 0;
    }
    std::cout << "one connection: " << positions << " positions in " << elapsed_s << " s ("
              << static_cast<double>(positions) / elapsed_s << " a second, " << player_of.size()
              << " Plays)\n";
    EXPECT_GE(positions, 2u);
    EXPECT_LE(static_cast<double>(positions), 2.0 + 50.0 * elapsed_s)
        << positions << " positions in " << elapsed_s << " s of " << player_of.size() << " Plays";
}

TEST_F(DaemonPositions, ManyConnectionsTogetherGetAtMost100PositionsASecond) {
    auto watcher = daemon.client();
    std::vector<std::unique_ptr<testing::HapticsClient>> players;
    for (int i = 0; i < 4; ++i) {
        players.push_back(daemon.client());
    }
    std::map<std::uint64_t, std::size_t> player_of;
    const double elapsed_s = stream(players, *watcher, player_of);
    std::vector<std::size_t> each(players.size());
    std::size_t positions = 0;
    for (const auto& seen : watcher->signals()) {
        if (seen.name == "PlaybackPosition") {
            ++positions;
            ++each.at(player_of.at(seen.id));
        }
    }
    std::cout << "four connections: " << positions << " positions in " << elapsed_s << " s ("
              << static_cast<double>(positions) / elapsed_s << " a second, " << player_of.size()
              << " Plays)\n";
    EXPECT_LE(static_cast<double>(positions), 4.0 + 100.0 * elapsed_s)
        << positions << " positions in " << elapsed_s << " s of " << player_of.size() << " Plays";
    for (const auto count : each) {
        EXPECT_LE(static_cast<double>(count), 2.0 + 50.0 * elapsed_s);
    }
}

}  // namespace
}  // namespace vibscore
