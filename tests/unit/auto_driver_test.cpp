// driver = auto: the choice itself against answers a test gives (which device discovery finds,
// which backend opens), then the actuator host choosing among real backends (sim, timed_output
// on a temporary sysfs tree, evdev discovery in an empty folder) and choosing again on reload.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "daemon/actuator_host.hpp"
#include "daemon/config.hpp"
#include "daemon/drivers/auto_driver.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

constexpr const char* kNoVibra =
    "evdev: no force-feedback device in /dev/input (4 event devices, none with force feedback)";

// A search whose backends open or fail as `failing` says, recording what was tried in order.
class AutoChoiceTest : public ::testing::Test {
  protected:
    AutoChoiceTest() {
        search.where = "/etc/vibscore/vibscored.conf:8";
        search.discover = []() -> DiscoveredDevice { throw DeviceError(kNoVibra); };
        search.open = [this](const std::string& driver) -> std::unique_ptr<Actuator> {
            opened.push_back(driver);
            if (const auto failure = failing.find(driver); failure != failing.end()) {
                throw DeviceError(failure->second);
            }
            return make_actuator("sim", {});
        };
    }

    AutoSearch search;
    std::map<std::string, std::string> failing;  // driver: the error its open throws
    std::vector<std::string> opened;
};

TEST_F(AutoChoiceTest, TakesTheForceFeedbackDeviceUdevTagsAsTheVibra) {
    search.discover = [] { return DiscoveredDevice{"/dev/input/event3", true}; };
    const auto choice = choose_driver(search);
    EXPECT_EQ(choice.driver, "evdev");
    EXPECT_FALSE(choice.fell_back);
    EXPECT_NE(choice.actuator, nullptr);
    EXPECT_THAT(opened, ElementsAre("evdev"));
    EXPECT_EQ(choice.reason,
              "driver = auto (/etc/vibscore/vibscored.conf:8): evdev on /dev/input/event3, the "
              "force-feedback device udev tags FEEDBACKD_TYPE=vibra");
}

TEST_F(AutoChoiceTest, SaysSoWhenTheDeviceItTakesIsOnlyTheFirstWithForceFeedback) {
    search.discover = [] { return DiscoveredDevice{"/dev/input/event7", false}; };
    search.where.clear();
    const auto choice = choose_driver(search);
    EXPECT_EQ(choice.driver, "evdev");
    EXPECT_EQ(choice.reason,
              "driver = auto: evdev on /dev/input/event7, the first force-feedback device (udev "
              "tags none FEEDBACKD_TYPE=vibra)");
}

TEST_F(AutoChoiceTest, TriesTheDeviceEvdevNamesWithoutDiscovery) {
    search.evdev_device = "/dev/input/event2";
    search.discover = []() -> DiscoveredDevice {
        ADD_FAILURE() << "discovery ran";
        throw DeviceError("discovery ran");
    };
    const auto choice = choose_driver(search);
    EXPECT_EQ(choice.driver, "evdev");
    EXPECT_THAT(choice.reason, HasSubstr("evdev on /dev/input/event2, the device [evdev] names"));
}

TEST_F(AutoChoiceTest, WithoutAVibraTakesTheFirstConfiguredSectionThatOpens) {
    search.sections = {{"gpio-erm", "v.conf:40"}, {"led-vibrator", "v.conf:60"}};
    failing["gpio-erm"] = "gpio-erm: /dev/gpiochip0: No such file or directory";
    const auto choice = choose_driver(search);
    EXPECT_EQ(choice.driver, "led-vibrator");
    EXPECT_FALSE(choice.fell_back);
    EXPECT_THAT(opened, ElementsAre("gpio-erm", "led-vibrator"));  // evdev found nothing to open
    EXPECT_EQ(choice.reason,
              "driver = auto (/etc/vibscore/vibscored.conf:8): led-vibrator on the device "
              "[led-vibrator] (v.conf:60) configures (before it: " +
                  std::string(kNoVibra) +
                  "; [gpio-erm] (v.conf:40): gpio-erm: /dev/gpiochip0: No such file or "
                  "directory)");
}

TEST_F(AutoChoiceTest, TriesTheConfiguredSectionsInItsOrderNotTheFilesOrTheAlphabets) {
    // sysfs-pwm before led-vibrator, though the alphabet (and this file) put it after.
    search.sections = {
        {"led-vibrator", "v.conf:3"}, {"sysfs-pwm", "v.conf:9"}, {"timed-output", "v.conf:1"}};
    EXPECT_EQ(choose_driver(search).driver, "sysfs-pwm");
    failing["sysfs-pwm"] = "no pwmchip0";
    opened.clear();
    EXPECT_EQ(choose_driver(search).driver, "led-vibrator");
    EXPECT_THAT(opened, ElementsAre("sysfs-pwm", "led-vibrator"));
}

TEST_F(AutoChoiceTest, NeverOpensABackendWhoseSectionIsNotConfiguredNorAModuleNorSimBeforeTheEnd) {
    search.sections = {{"sim", "v.conf:20"}, {"trace", "v.conf:30"}, {"virtual-vibra", ""}};
    const auto choice = choose_driver(search);
    EXPECT_THAT(opened, ElementsAre("sim"));
    EXPECT_TRUE(choice.fell_back);
}

TEST_F(AutoChoiceTest, FindingNothingFallsBackToSimSayingWhatWasSearchedAndHowToConfigure) {
    const auto choice = choose_driver(search);
    EXPECT_EQ(choice.driver, "sim");
    EXPECT_TRUE(choice.fell_back);
    EXPECT_NE(choice.actuator, nullptr);
    EXPECT_THAT(choice.reason,
                StartsWith("driver = auto (/etc/vibscore/vibscored.conf:8) found no actuator, so "
                           "driver sim plays (nothing vibrates). Searched: " +
                           std::string(kNoVibra) +
                           "; no [gpio-erm], [gpio-lra], [sysfs-pwm], [led-vibrator] or "
                           "[timed-output] section is configured. To drive yours: "));
    EXPECT_THAT(choice.reason, HasSubstr("FEEDBACKD_TYPE=vibra"));
    EXPECT_THAT(choice.reason, HasSubstr("driver = NAME and its [NAME] section in vibscored.conf"));
}

TEST_F(AutoChoiceTest, AFoundDeviceThatWillNotOpenIsPassedOverAndNamedInTheReason) {
    search.discover = [] { return DiscoveredDevice{"/dev/input/event3", true}; };
    search.sections = {{"timed-output", "v.conf:70"}};
    failing["evdev"] = "evdev: /dev/input/event3: cannot open: Permission denied";
    failing["timed-output"] = "timed-output: no /sys/class/timed_output/vibrator";
    const auto choice = choose_driver(search);
    EXPECT_TRUE(choice.fell_back);
    EXPECT_THAT(opened, ElementsAre("evdev", "timed-output", "sim"));
    EXPECT_THAT(choice.reason,
                HasSubstr("Searched: evdev: /dev/input/event3: cannot open: Permission denied; "
                          "[timed-output] (v.conf:70): timed-output: no "
                          "/sys/class/timed_output/vibrator; no [gpio-erm], [gpio-lra], "
                          "[sysfs-pwm] or [led-vibrator] section is configured."));
}

TEST_F(AutoChoiceTest, WithEverySectionConfiguredNoneIsSaidMissing) {
    for (const std::string driver : kAutoConfiguredDrivers) {
        search.sections[driver] = "";
        failing[driver] = driver + " failed";
    }
    const auto choice = choose_driver(search);
    EXPECT_TRUE(choice.fell_back);
    EXPECT_THAT(choice.reason, HasSubstr("[timed-output]: timed-output failed. To drive yours"));
    EXPECT_THAT(choice.reason, Not(HasSubstr("section is configured")));
}

TEST_F(AutoChoiceTest, ABadSettingIsAnErrorNotPassedOver) {
    search.sections = {{"gpio-erm", "v.conf:40"}, {"timed-output", "v.conf:70"}};
    search.open = [](const std::string& driver) -> std::unique_ptr<Actuator> {
        if (driver == "gpio-erm") {
            throw SettingError("carrier-hz", "gpio-erm: carrier-hz = \"fast\" is not a number");
        }
        return make_actuator("sim", {});
    };
    EXPECT_THROW(choose_driver(search), SettingError);
}

}  // namespace
}  // namespace vibscore::drivers

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// The host with driver = auto on a machine with no force-feedback device (discovery looks in an
// empty folder) and, when configured, a timed_output vibrator on a temporary sysfs tree.
class AutoHostTest : public ::testing::Test {
  protected:
    AutoHostTest() {
        std::filesystem::create_directories(input.path() / "by-path");
        std::filesystem::create_directories(sysfs.path() / "class/timed_output/vibrator");
        sysfs.write("class/timed_output/vibrator/enable", "0");
        config =
            parse_config("[daemon]\ndriver = auto\n[evdev]\ninput-dir = " + input.path().string() +
                             "\n[sim]\nmodel = erm\n",
                         "v.conf");
    }
    void configure_timed_output() {
        config.driver_settings["timed-output"] = {{"sysfs-root", sysfs.path().string()}};
    }

    vibscore::testing::TempDir input, sysfs;
    DaemonConfig config;
};

TEST_F(AutoHostTest, FindingNothingRunsSimAndSaysWhereItLooked) {
    const ActuatorHost host(config);
    EXPECT_EQ(host.driver(), "sim");
    EXPECT_THAT(
        host.reason(),
        StartsWith("driver = auto (v.conf:2) found no actuator, so driver sim plays (nothing "
                   "vibrates). Searched: evdev: no force-feedback device in " +
                   input.path().string() + " (0 event devices, none with force feedback)"));
}

TEST_F(AutoHostTest, TakesAConfiguredTimedOutputVibratorAndSaysWhichSection) {
    configure_timed_output();
    const ActuatorHost host(config);
    EXPECT_EQ(host.driver(), "timed-output");
    EXPECT_THAT(host.reason(), StartsWith("driver = auto (v.conf:2): timed-output on the device "
                                          "[timed-output] configures (before it: evdev: no "
                                          "force-feedback device in "));
}

TEST_F(AutoHostTest, AReloadChoosesAgainAfterAFallBackToSimButNotAfterAFind) {
    ActuatorHost host(config);
    ASSERT_EQ(host.driver(), "sim");
    configure_timed_output();  // the vibrator appeared and the reload tells where
    EXPECT_TRUE(host.follow_config());
    EXPECT_EQ(host.driver(), "timed-output");
    EXPECT_FALSE(host.follow_config());  // found: a reload leaves it be
    EXPECT_EQ(host.driver(), "timed-output");
}

TEST_F(AutoHostTest, ARunTimeSwitchSaysSoAndAReloadReturnsToTheChoice) {
    configure_timed_output();
    ActuatorHost host(config);
    host.switch_to("sim");
    EXPECT_EQ(host.driver(), "sim");
    EXPECT_EQ(host.reason(),
              "switched at run time (SwitchDriver, vibscore driver sim); a reload or a restart "
              "returns to the configuration's driver = auto");
    EXPECT_TRUE(host.follow_config());
    EXPECT_EQ(host.driver(), "timed-output");
    EXPECT_THAT(host.reason(), StartsWith("driver = auto (v.conf:2): "));
}

TEST_F(AutoHostTest, ANamedDriverSaysItWasConfigured) {
    config.driver = "sim";
    ActuatorHost host(config);
    EXPECT_THAT(host.reason(), StartsWith("configured"));
    EXPECT_THAT(host.reason(), HasSubstr("driver = sim"));
    // Named after auto ran sim: a reload follows the file's new word.
    config.driver = "auto";
    configure_timed_output();
    EXPECT_TRUE(host.follow_config());
    EXPECT_EQ(host.driver(), "timed-output");
}

}  // namespace
}  // namespace vibscore::daemon

namespace vibscore::daemon {
namespace {

TEST(ShippedConfiguration, SaysDriverAutoAndReadsWithoutError) {
    const auto file =
        std::filesystem::path(vibscore::testing::required_env("VIBSCORE_CLEFS")).parent_path() /
        "etc/vibscored.conf";
    const DaemonConfig config = load_config(file);
    EXPECT_EQ(config.driver, "auto");
    // No backend's section is configured: auto tries evdev alone, then runs sim.
    for (const std::string driver : drivers::kAutoConfiguredDrivers) {
        EXPECT_FALSE(config.driver_settings.contains(driver)) << driver;
    }
}

}  // namespace
}  // namespace vibscore::daemon
