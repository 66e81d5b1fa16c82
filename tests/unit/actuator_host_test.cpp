// The actuator host without a bus: opening the configured backend, switching at run time with
// the configured settings, falling back when a backend will not open, following a reloaded
// configuration. Real backends: the simulated actuator, and sysfs ones on a temporary tree.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "daemon/actuator_host.hpp"
#include "daemon/config.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "tests/support/crash_signal.hpp"
#include "tests/support/finished_reasons.hpp"
#include "tests/support/support.hpp"
#include "tests/support/test_modules.hpp"

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

TEST_F(ActuatorHostTest, AnUnknownConfiguredDriverOrADeviceThatWillNotOpenNamesItsLine) {
    config = parse_config("[daemon]\ndriver = evdevv\n", "v.conf", config);
    EXPECT_THAT([&] { ActuatorHost host_of_bad{config}; },
                ::testing::ThrowsMessage<std::invalid_argument>(
                    ::testing::StartsWith("v.conf:2: unknown driver \"evdevv\" (available: sim")));
    config = parse_config("[daemon]\ndriver = evdev\n[evdev]\ndevice = /nonexistent/event99\n",
                          "w.conf");
    EXPECT_THAT([&] { ActuatorHost host_of_bad{config}; },
                ::testing::ThrowsMessage<drivers::DeviceError>(
                    ::testing::StartsWith("w.conf:3: evdev /nonexistent/event99: ")));
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

    // Another drivers directory does not reopen a built-in backend.
    config.drivers_dir = sysfs.path();
    config.modules = drivers::scan_driver_modules(config.drivers_dir);
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

// ---- driver modules: a module that crashes must not crash the daemon on every start

class ActuatorHostModulesTest : public ::testing::Test {
  protected:
    ActuatorHostModulesTest() {
        config.driver_settings["sim"] = {};
        config.module_record = store.path() / kModuleRecordFile;
    }
    void scan() { config.modules = drivers::scan_driver_modules(modules.path()); }
    bool recorded() const { return std::filesystem::exists(config.module_record); }
    // The host as vibscored makes it, in a child that crashes in the module's apply().
    void crash_in_apply() {
        const pid_t child = ::fork();
        if (child == 0) {
            ActuatorHost host(config);
            host.actuator().apply({0.5, 0.0});
            ::_exit(0);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == testing::kCrashSignal) << status;
    }

    vibscore::testing::ModulesDir modules;
    vibscore::testing::TempDir store;
    DaemonConfig config;
};

TEST_F(ActuatorHostModulesTest, AStartAfterACrashInTheConfiguredModuleRunsSimAndSaysSo) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    const auto segv = modules.add("segv");
    scan();
    config.driver = "segv";
    crash_in_apply();
    ASSERT_TRUE(recorded()) << "the crashed run's record";
    EXPECT_EQ(read_module_record(config.module_record)->name, "segv");

    ::testing::internal::CaptureStderr();
    ActuatorHost host(config);
    const std::string log = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(host.driver(), "sim");
    EXPECT_THAT(log, HasSubstr("driver module segv (" + segv.string() +
                               ") was in use when vibscored last ended without closing it (a "
                               "crash in it, a hang, or a kill); running driver sim instead, so "
                               "the daemon serves. `vibscore driver segv` or a reload tries it "
                               "again"));
    EXPECT_FALSE(recorded());
    // Without the record, a restart now would try it again: a reload does that at once.
    EXPECT_TRUE(host.follow_config());
    EXPECT_EQ(host.driver(), "segv");
    EXPECT_TRUE(recorded());
}

TEST_F(ActuatorHostModulesTest, AModuleClosedCleanlyLeavesNoRecordAndTheNextStartRunsIt) {
    modules.add("counted");
    scan();
    config.driver = "counted";
    {
        ActuatorHost host(config);
        EXPECT_TRUE(recorded());
        host.switch_to("sim");
        EXPECT_FALSE(recorded()) << "closed by the switch";
        host.switch_to("counted");
        EXPECT_TRUE(recorded());
    }
    EXPECT_FALSE(recorded()) << "closed when the daemon ends";
    ActuatorHost again(config);
    EXPECT_EQ(again.driver(), "counted");
}

TEST_F(ActuatorHostModulesTest, ARecordOfAModuleNotConfiguredIsAWarningOnly) {
    modules.add("counted");
    scan();
    config.driver = "counted";
    std::ofstream(config.module_record) << "segv\n/somewhere/segv.so\n";
    ::testing::internal::CaptureStderr();
    ActuatorHost host(config);
    EXPECT_THAT(::testing::internal::GetCapturedStderr(),
                HasSubstr("vibscored last ended while driver module segv (/somewhere/segv.so) was "
                          "in use, without closing it"));
    EXPECT_EQ(host.driver(), "counted");
}

TEST_F(ActuatorHostModulesTest, SafeOffOpensTheCrashedModuleAndLeavesTheRecordForTheNextStart) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    modules.add("segv");
    scan();
    config.driver = "segv";
    crash_in_apply();
    DaemonConfig safe_off = config;
    safe_off.module_record.clear();  // as read_config() leaves it for --safe-off
    {
        ActuatorHost host(safe_off);
        EXPECT_EQ(host.driver(), "segv") << "its device is the one to switch off";
        host.actuator().off();
    }
    EXPECT_TRUE(recorded());
    ActuatorHost serving(config);
    EXPECT_EQ(serving.driver(), "sim");
}

TEST_F(ActuatorHostModulesTest, AConfiguredModuleRefusedAtTheScanRunsSimAndSaysWhy) {
    if (testing::kSanitizerOwnsCrashes) {
        GTEST_SKIP() << "AddressSanitizer's handler decides how a crashing module's process ends";
    }
    const auto crash = modules.add("crash-at-load");
    const auto writable = modules.add("counted", "writable.so");
    std::filesystem::permissions(writable, std::filesystem::perms(0666));
    scan();
    config.driver = "crash-at-load";
    ::testing::internal::CaptureStderr();
    ActuatorHost host(config);
    EXPECT_THAT(::testing::internal::GetCapturedStderr(),
                HasSubstr("driver crash-at-load: module " + crash.string() +
                          " is not loaded: crashed while loading (" + testing::kCrashSignalName +
                          "); running driver sim "
                          "instead"));
    EXPECT_EQ(host.driver(), "sim");
    EXPECT_FALSE(recorded());
    config.driver = "writable";
    ActuatorHost other(config);
    EXPECT_EQ(other.driver(), "sim");
    EXPECT_THAT([&] { other.switch_to("writable"); },
                ::testing::ThrowsMessage<std::invalid_argument>(
                    HasSubstr("is writable by group or others (mode 0666)")));
}

TEST_F(ActuatorHostModulesTest, AReloadReopensAModuleOnlyWhenItsFileChanged) {
    const auto module = modules.add_example();
    config.driver_settings["trace"] = {{"path", (store.path() / "trace.log").string()}};
    scan();
    config.driver = "trace";
    ActuatorHost host(config);
    scan();  // a reload scans again: the same file
    EXPECT_FALSE(host.follow_config());
    std::filesystem::remove(module);
    modules.add_example();  // an upgrade
    scan();
    EXPECT_TRUE(host.follow_config());
    EXPECT_EQ(host.driver(), "trace");
}

TEST_F(ActuatorHostModulesTest, ListsTheModulesOfTheLastScan) {
    modules.add("counted");
    scan();
    config.driver = "sim";
    ActuatorHost host(config);
    EXPECT_EQ(host.drivers().back().name, "counted");
    modules.add_example();
    scan();
    host.follow_config();
    EXPECT_EQ(host.drivers().back().name, "trace");
}

}  // namespace
}  // namespace vibscore::daemon
