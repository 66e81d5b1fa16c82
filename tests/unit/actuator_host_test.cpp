// The actuator host without a bus: opening the configured backend, switching at run time with
// the configured settings, falling back when a backend will not open, following a reloaded
// configuration. Real backends: the simulated actuator, and sysfs ones on a temporary tree.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "daemon/actuator_host.hpp"
#include "daemon/config.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "tests/support/finished_reasons.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A playback that goes on until something ends it.
PlaybackRequest endless() {
    PlaybackRequest request;
    request.label = "endless";
    render::Cue drive;
    drive.amplitude = 0.5;
    request.cues = std::make_shared<render::CueList>(std::vector<render::Cue>{drive});
    request.duration_s = 10.0;
    request.repeat = -1;
    return request;
}

class ActuatorHostTest : public ::testing::Test {
  protected:
    ActuatorHostTest() {
        config.driver = "sim";
        config.driver_settings["sim"] = {{"model", "lra"}, {"max-on-time-ms", "3000"}};
        // A timed_output vibrator on a temporary sysfs tree, and an evdev device that is not
        // there: a backend that opens, and one that never does.
        std::filesystem::create_directories(sysfs.path() / "class/timed_output/vibrator");
        sysfs.write("class/timed_output/vibrator/enable", "0");
        config.driver_settings["timed-output"] = {{"sysfs-root", sysfs.path().string()}};
        config.driver_settings["evdev"] = {{"device", "/nonexistent/event99"}};
    }

    // The host and a player on its actuator, as vibscored wires them.
    void start() {
        host.emplace(config);
        player.emplace(loop, host->actuator(), listener);
        host->attach(*player);
        host->on_change([this] { ++changes; });
    }

    vibscore::testing::TempDir sysfs;
    DaemonConfig config;
    EventLoop loop;
    vibscore::testing::FinishedReasons listener;
    std::optional<ActuatorHost> host;
    std::optional<Player> player;
    int changes = 0;
};

TEST_F(ActuatorHostTest, OpensTheConfiguredDriverWithItsSettings) {
    start();
    EXPECT_EQ(host->driver(), "sim");
    EXPECT_EQ(host->capabilities().max_on_time_s, 3.0);
}

TEST_F(ActuatorHostTest, AConfiguredDriverThatWillNotOpenIsAnError) {
    config.driver = "evdev";
    EXPECT_THROW(ActuatorHost{config}, drivers::DeviceError);
}

TEST_F(ActuatorHostTest, ListsTheBuiltInDrivers) {
    start();
    std::vector<std::string> names;
    for (const auto& driver : host->drivers()) {
        names.push_back(driver.name);
    }
    EXPECT_THAT(names, ::testing::IsSupersetOf({"sim", "evdev", "gpio-erm", "gpio-lra", "sysfs-pwm",
                                                "led-vibrator", "timed-output"}));
}

TEST_F(ActuatorHostTest, ASwitchEndsPlaybackAndThePlayerPlaysOnTheNewBackend) {
    start();
    player->play(endless());
    host->switch_to("timed-output");
    EXPECT_EQ(host->driver(), "timed-output");
    EXPECT_THAT(listener.reasons, ElementsAre("driver-switch"));
    EXPECT_EQ(changes, 1);

    player->play(endless());
    // The first drive reached the new backend, its kernel timer armed with the time until the
    // score switches off: strength 0.5 on an on/off device is on for half of a 40 ms pulse
    // (less what passed since the playback started).
    const auto enable_ms = std::stol(
        vibscore::testing::read_file(sysfs.path() / "class/timed_output/vibrator/enable"));
    EXPECT_GT(enable_ms, 0);
    EXPECT_LE(enable_ms, 20);
}

TEST_F(ActuatorHostTest, ASwitchTakesTheSettingsConfiguredForTheNewDriver) {
    start();
    config.driver_settings["sim"] = {{"model", "erm"}, {"max-on-time-ms", "1500"}};
    host->switch_to("sim");
    EXPECT_EQ(host->capabilities().max_on_time_s, 1.5);
}

TEST_F(ActuatorHostTest, ADriverThatWillNotOpenLeavesThePreviousOneRunning) {
    start();
    EXPECT_THROW(host->switch_to("evdev"), drivers::DeviceError);
    EXPECT_EQ(host->driver(), "sim");
    EXPECT_EQ(changes, 1);  // told even so: the backend was reopened
    const auto id = player->play(endless());
    EXPECT_EQ(player->current_id(), id);
}

TEST_F(ActuatorHostTest, AnUnknownDriverOrABadSettingIsAnInvalidArgument) {
    start();
    EXPECT_THROW(host->switch_to("no-such-driver"), std::invalid_argument);
    config.driver_settings["timed-output"]["duration-ms"] = "forever";
    EXPECT_THROW(host->switch_to("timed-output"), std::invalid_argument);
    EXPECT_EQ(host->driver(), "sim");
}

TEST_F(ActuatorHostTest, ABadBackendSettingNamesTheFileAndLineItCameFrom) {
    config = parse_config("[daemon]\ndriver = sim\n[sim]\nmodel = lra\nmax-on-time-ms = ever\n",
                          "v.conf", config);
    try {
        ActuatorHost host_of_bad{config};
        ADD_FAILURE() << "no error";
    } catch (const drivers::SettingError& error) {
        EXPECT_THAT(error.what(), ::testing::StartsWith("v.conf:5: "));
        EXPECT_THAT(error.what(), HasSubstr("\"ever\""));
    }
}

TEST_F(ActuatorHostTest, AnUnknownBackendKeyListsEveryKeyTheBackendTakesTheCommonOnesToo) {
    config = parse_config("[daemon]\ndriver = sim\n[sim]\nmodle = erm\n", "v.conf", config);
    try {
        ActuatorHost host_of_bad{config};
        ADD_FAILURE() << "no error";
    } catch (const drivers::SettingError& error) {
        EXPECT_THAT(error.what(), ::testing::StartsWith("v.conf:4: "));
        EXPECT_THAT(error.what(), HasSubstr("model"));
        EXPECT_THAT(error.what(), HasSubstr("max-on-time-ms"));
        EXPECT_THAT(error.what(), HasSubstr("pulse-period-ms"));
    }
}

TEST_F(ActuatorHostTest, WhenNeitherBackendOpensEveryPlaybackFailsWithBothReasons) {
    config.driver = "timed-output";
    start();
    std::filesystem::remove_all(sysfs.path() / "class");  // the device went away
    EXPECT_THROW(host->switch_to("evdev"), drivers::DeviceError);
    EXPECT_EQ(host->driver(), "none");

    listener.reasons.clear();
    player->play(endless());
    ASSERT_EQ(listener.reasons.size(), 1u);
    EXPECT_THAT(listener.reasons[0], HasSubstr("device-error: no actuator: driver evdev failed"));
    EXPECT_THAT(listener.reasons[0], HasSubstr("driver timed-output would not reopen"));

    config.driver_settings["sim"] = {};
    host->switch_to("sim");  // the next switch recovers
    EXPECT_EQ(host->driver(), "sim");
}

TEST_F(ActuatorHostTest, FollowingTheConfigurationSwitchesOnlyWhenWhatRunsDiffers) {
    start();
    EXPECT_FALSE(host->follow_config());
    EXPECT_EQ(changes, 0);

    config.driver_settings["sim"]["q"] = "20";
    EXPECT_TRUE(host->follow_config());
    EXPECT_EQ(changes, 1);

    config.driver = "timed-output";
    EXPECT_TRUE(host->follow_config());
    EXPECT_EQ(host->driver(), "timed-output");

    config.drivers_dir = sysfs.path();
    EXPECT_TRUE(host->follow_config());  // modules may have changed
    EXPECT_FALSE(host->follow_config());
}

TEST_F(ActuatorHostTest, ADeclarationChangeReopensOnlyTheSimWhichSimulatesIt) {
    config.driver_settings["sim"] = {};
    start();
    actuator::Declaration board;
    board.kind = actuator::Kind::erm;
    board.brake = actuator::Brake::reverse;
    config.actuator = board;
    EXPECT_TRUE(host->follow_config());  // the sim is made of the declaration
    EXPECT_TRUE(host->capabilities().reverse);
    EXPECT_FALSE(host->follow_config());

    config.driver = "timed-output";
    EXPECT_TRUE(host->follow_config());
    player->play(endless());
    const int announced = changes;
    config.actuator->rated_drive = 0.6;  // the board's vibra is whatever it is
    EXPECT_FALSE(host->follow_config());
    EXPECT_TRUE(player->current_id().has_value()) << "the backend was not reopened";
    EXPECT_EQ(changes, announced + 1) << "the new declaration is announced";
    EXPECT_EQ(host->declaration(), config.actuator);
    EXPECT_FALSE(host->follow_config());
    EXPECT_EQ(changes, announced + 1);
}

TEST_F(ActuatorHostTest, AfterASwitchOverTheBusAReloadReturnsToTheConfiguredDriver) {
    start();
    host->switch_to("timed-output");
    EXPECT_TRUE(host->follow_config());
    EXPECT_EQ(host->driver(), "sim");
}

}  // namespace
}  // namespace vibscore::daemon
