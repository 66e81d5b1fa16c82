// SIGHUP's work without a daemon: a reloaded configuration checked before it changes anything,
// then applied to the request rate and the backend.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "daemon/reload.hpp"
#include "tests/support/finished_reasons.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

class ReloadTest : public ::testing::Test {
  protected:
    ReloadTest() {
        running.driver = "sim";
        running.store = "/var/lib/vibscore";
        running.shipped = "/usr/share/vibscore/clefs";
        running.driver_settings["sim"] = {{"model", "lra"}};
        host.emplace(running);
        player.emplace(loop, host->actuator(), reasons);
        host->attach(*player);
        PlaybackRequest request;
        render::Cue drive;
        drive.amplitude = 0.5;
        request.cues = std::make_shared<render::CueList>(std::vector<render::Cue>{drive});
        request.duration_s = 10.0;
        request.repeat = -1;
        player->play(request);
    }

    DaemonConfig running;
    EventLoop loop;
    vibscore::testing::FinishedReasons reasons;
    std::optional<ActuatorHost> host;
    std::optional<Player> player;
};

TEST_F(ReloadTest, TheSameConfigurationAgainChangesNothingAndPlaybackGoesOn) {
    reload_config(running, running, *host);
    EXPECT_THAT(reasons.reasons, IsEmpty());
    EXPECT_TRUE(player->current_id().has_value());
}

TEST_F(ReloadTest, ANewClefMapIsTheRunningOneAtOnceAndPlaybackGoesOn) {
    DaemonConfig fresh = running;
    fresh.device_clefs.by_written["lra-phone"] = "erm-phone";
    fresh.device_clefs.otherwise = "soft-shapes";
    reload_config(running, fresh, *host);
    EXPECT_EQ(running.device_clefs.for_written("lra-phone"), "erm-phone");
    EXPECT_EQ(running.device_clefs.for_written("shaker-sine-low"), "soft-shapes");
    EXPECT_EQ(describe(running.device_clefs), "lra-phone -> erm-phone, * -> soft-shapes");
    EXPECT_THAT(reasons.reasons, IsEmpty());
    EXPECT_TRUE(player->current_id().has_value());
}

TEST_F(ReloadTest, ANewActuatorWithFitAutoRefitsEveryClefItDoesNotMap) {
    actuator::Declaration erm;
    erm.kind = actuator::Kind::erm;
    DaemonConfig fresh = running;
    fresh.driver_settings["sim"] = {};  // the sim simulates the declared actuator
    fresh.actuator = erm;
    fresh.device_clefs.fit_to = erm;
    fresh.device_clefs.by_written["lra-phone"] = "erm-phone";
    reload_config(running, fresh, *host);
    EXPECT_EQ(running.device_clefs.for_written("lra-phone"), "erm-phone");
    EXPECT_EQ(running.device_clefs.for_written("soft-shapes"), "soft-shapes (fitted)");
    EXPECT_EQ(running.device_clefs.fit_to, erm);
}

// Admission reads the running limits at each request (haptics_service), so running is all there
// is to change.
TEST_F(ReloadTest, ANewRequestRateAppliesAtOnceWithoutTouchingTheBackend) {
    DaemonConfig fresh = running;
    fresh.requests_per_second = 5.0;
    fresh.request_burst = 1.0;
    reload_config(running, fresh, *host);
    EXPECT_EQ(running.requests_per_second, 5.0);
    EXPECT_EQ(running.request_burst, 1.0);
    EXPECT_THAT(reasons.reasons, IsEmpty());
}

TEST_F(ReloadTest, NewSettingsOfTheRunningDriverReopenItEndingPlayback) {
    DaemonConfig fresh = running;
    fresh.driver_settings["sim"]["max-on-time-ms"] = "2000";
    reload_config(running, fresh, *host);
    EXPECT_THAT(reasons.reasons, ElementsAre("driver-switch"));
    EXPECT_EQ(host->capabilities().max_on_time_s, 2.0);
    EXPECT_EQ(running.settings_of("sim").at("max-on-time-ms"), "2000");
}

TEST_F(ReloadTest, ABadSettingChangesNothingAtAll) {
    DaemonConfig fresh = running;
    fresh.requests_per_second = 5.0;
    fresh.driver_settings["sim"]["max-on-time-ms"] = "long";
    EXPECT_THROW(reload_config(running, fresh, *host), std::invalid_argument);
    EXPECT_EQ(running.requests_per_second, 50.0);
    EXPECT_FALSE(running.settings_of("sim").contains("max-on-time-ms"));
    EXPECT_THAT(reasons.reasons, IsEmpty());
}

// Each alone, so that neither hides behind the other: the warning must come for either change.
TEST_F(ReloadTest, AReloadThatChangesOnlyTheStoreKeepsItAndSaysItChangesOnlyOnRestart) {
    DaemonConfig fresh = parse_config("[daemon]\nstore = /elsewhere/store\n", "v.conf", running);
    ::testing::internal::CaptureStderr();
    reload_config(running, fresh, *host);
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(running.store, "/var/lib/vibscore");
    EXPECT_THAT(log, HasSubstr("v.conf:2: store = \"/elsewhere/store\" changes only on restart; "
                               "until then it stays /var/lib/vibscore"));
    EXPECT_THAT(log, Not(HasSubstr("shipped")));
}

TEST_F(ReloadTest, AReloadThatChangesOnlyTheShippedFolderKeepsItAndSaysItChangesOnlyOnRestart) {
    DaemonConfig fresh = running;
    fresh.shipped = "/elsewhere/clefs";
    ::testing::internal::CaptureStderr();
    reload_config(running, fresh, *host);
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(running.shipped, "/usr/share/vibscore/clefs");
    EXPECT_THAT(log, HasSubstr("shipped = \"/elsewhere/clefs\" changes only on restart; until "
                               "then it stays /usr/share/vibscore/clefs"));
    EXPECT_THAT(log, Not(HasSubstr("store")));
}

TEST_F(ReloadTest, AReloadThatChangesNeitherFolderSaysNothingAboutThem) {
    DaemonConfig fresh = running;
    fresh.separation_ms = 10.0;
    ::testing::internal::CaptureStderr();
    reload_config(running, fresh, *host);
    EXPECT_THAT(::testing::internal::GetCapturedStderr(), Not(HasSubstr("only on restart")));
}

TEST_F(ReloadTest, TheStoreAndShippedDirectoriesKeepTheirRunningValues) {
    DaemonConfig fresh = running;
    fresh.store = "/elsewhere/store";
    fresh.shipped = "/elsewhere/clefs";
    fresh.separation_ms = 10.0;
    reload_config(running, fresh, *host);
    EXPECT_EQ(running.store, "/var/lib/vibscore");
    EXPECT_EQ(running.shipped, "/usr/share/vibscore/clefs");
    EXPECT_EQ(running.separation_ms, 10.0);
}

// The first drive a one-note playback of strength 1 sends, as the sim's trace recorded it (the
// trace is appended to: the lines after what it held before).
double first_drive_sent(Player& player, const std::filesystem::path& trace) {
    PlaybackRequest request;
    request.cues = std::make_shared<render::CueList>(std::vector<render::Cue>{
        render::drive_at(0.0, 1.0, 175.0), render::drive_at(0.5, 0.0, 0.0)});
    request.duration_s = 1.0;
    const auto before = static_cast<std::streamoff>(std::filesystem::file_size(trace));
    player.play(request);
    player.stop_all("test");
    std::ifstream in(trace);
    in.seekg(before);
    std::string line;
    while (std::getline(in, line)) {
        if (line.starts_with("time_ns")) {
            continue;  // the header
        }
        const double amplitude = std::stod(line.substr(line.find(',') + 1));
        if (amplitude != 0.0) {
            return amplitude;
        }
    }
    return 0.0;
}

TEST_F(ReloadTest, TheDeclaredActuatorIsReloadedForTheSimAndTheNextPlay) {
    vibscore::testing::TempDir dir;
    const auto trace = dir.path() / "trace.csv";
    DaemonConfig fresh = running;
    fresh.driver_settings["sim"] = {{"trace", trace.string()}};
    actuator::Declaration board;
    board.kind = actuator::Kind::erm;
    board.rated_drive = 0.5;
    board.brake = actuator::Brake::reverse;
    board.compensation = false;
    fresh.actuator = board;
    reload_config(running, fresh, *host);
    EXPECT_EQ(running.actuator, board);
    EXPECT_TRUE(host->capabilities().reverse);
    EXPECT_EQ(first_drive_sent(*player, trace), 0.5);  // strength 1 is the rated drive

    DaemonConfig undeclared = running;
    undeclared.actuator.reset();
    reload_config(running, undeclared, *host);
    EXPECT_FALSE(host->capabilities().reverse);
    EXPECT_EQ(first_drive_sent(*player, trace), 1.0);  // as written again
}

TEST_F(ReloadTest, AnUnknownDriverChangesNothingAndNamesTheLineThatNamesIt) {
    const DaemonConfig fresh = parse_config("[daemon]\n\ndriver = evdevv\n", "v.conf", running);
    EXPECT_THAT([&] { reload_config(running, fresh, *host); },
                ::testing::ThrowsMessage<std::invalid_argument>(::testing::StartsWith(
                    "v.conf:3: unknown driver \"evdevv\" (available: sim, evdev")));
    EXPECT_EQ(host->driver(), "sim");
    EXPECT_EQ(running.driver, "sim");
    EXPECT_THAT(reasons.reasons, IsEmpty()) << "the playback was not stopped for it";
}

TEST_F(ReloadTest, ADriverThatWillNotOpenLeavesThePreviousOneRunning) {
    DaemonConfig fresh = running;
    fresh.driver = "evdev";
    fresh.driver_settings["evdev"] = {{"device", "/nonexistent/event99"}};
    EXPECT_THROW(reload_config(running, fresh, *host), drivers::DeviceError);
    EXPECT_EQ(host->driver(), "sim");
}

}  // namespace
}  // namespace vibscore::daemon
