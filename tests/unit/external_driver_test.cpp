// Driver modules through the C ABI (include/vibscore/driver.h), with the example module
// examples/driver/trace_driver.c built by meson.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "daemon/drivers/available.hpp"
#include "daemon/drivers/configured_actuator.hpp"
#include "daemon/drivers/external_driver.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using testing::TempDir;

std::filesystem::path example_drivers() {
    return testing::required_env("VIBSCORE_EXAMPLE_DRIVERS");
}

// The trace lines without their timestamps.
std::vector<std::string> commands(const std::filesystem::path& trace) {
    std::ifstream in(trace);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line.substr(line.find(' ') + 1));
    }
    return lines;
}

TEST(ExternalDriver, TheExampleModuleIsListedAfterTheBuiltInOnes) {
    const auto drivers = available_drivers(example_drivers());
    ASSERT_GE(drivers.size(), 2u);
    EXPECT_EQ(drivers.front().name, "sim");
    EXPECT_EQ(drivers.back().name, "trace");
    EXPECT_THAT(drivers.back().description, HasSubstr("(trace.so)"));
    EXPECT_EQ(available_drivers().size(), drivers.size() - 1);  // no directory: built-in only
}

TEST(ExternalDriver, CommandsReachTheModuleThroughTheCAbi) {
    TempDir dir;
    const auto trace = dir.path() / "trace.log";
    {
        auto actuator = make_actuator(
            "trace", {{"path", trace.string()}, {"max-on-time-ms", "1500"}}, example_drivers());
        EXPECT_EQ(actuator->driver_name(), "trace");
        const auto capabilities = actuator->capabilities();
        EXPECT_TRUE(capabilities.amplitude_control);
        EXPECT_TRUE(capabilities.frequency_control);
        EXPECT_FALSE(capabilities.effect_memory);    // the module has no prepare()
        EXPECT_EQ(capabilities.max_on_time_s, 1.5);  // the common setting, kept by the daemon
        actuator->apply({0.5, 170.0});
        actuator->off();
    }
    EXPECT_THAT(commands(trace), ElementsAre("open", "apply 0.500000 170.000", "off", "close"));
    std::ifstream in(trace);
    std::string first;
    std::getline(in, first);
    EXPECT_THAT(first, MatchesRegex("[0-9]+ open"));
}

TEST(ExternalDriver, AnOnOffModuleReportsNoAmplitudeControl) {
    TempDir dir;
    auto actuator =
        make_actuator("trace", {{"path", (dir.path() / "t.log").string()}, {"on-off", "true"}},
                      example_drivers());
    EXPECT_FALSE(actuator->capabilities().amplitude_control);
}

TEST(ExternalDriver, AModuleThatReportsReverseDriveGetsNegativeAmplitudes) {
    TempDir dir;
    const auto trace = dir.path() / "t.log";
    {
        auto actuator = make_actuator("trace", {{"path", trace.string()}, {"reverse", "true"}},
                                      example_drivers());
        EXPECT_TRUE(actuator->capabilities().reverse);
        actuator->apply({-1.0, 175.0});
    }
    EXPECT_THAT(commands(trace), ElementsAre("open", "apply -1.000000 175.000", "close"));
}

TEST(ExternalDriver, AModuleWithoutReverseDriveNeverSeesANegativeAmplitude) {
    TempDir dir;
    const auto trace = dir.path() / "t.log";
    {
        auto actuator = make_actuator("trace", {{"path", trace.string()}}, example_drivers());
        EXPECT_FALSE(actuator->capabilities().reverse);
        actuator->apply({-0.5, 175.0});
    }
    EXPECT_THAT(commands(trace), ElementsAre("open", "apply 0.000000 175.000", "close"));
}

TEST(ExternalDriver, AModuleBuiltForAbiVersion1StillLoadsAndIsNeverDrivenBackwards) {
    TempDir dir;
    const std::filesystem::path old_modules = testing::required_env("VIBSCORE_OLD_ABI_DRIVERS");
    const auto trace = dir.path() / "old.log";
    {
        auto actuator = make_actuator("oldabi", {{"path", trace.string()}}, old_modules);
        // It sets bit 5, which meant nothing in version 1.
        EXPECT_FALSE(actuator->capabilities().reverse);
        EXPECT_TRUE(actuator->capabilities().amplitude_control);
        actuator->apply({-0.5, 0.0});
        actuator->apply({0.25, 0.0});
    }
    EXPECT_EQ(testing::read_file(trace), "apply 0.000\napply 0.250\n");
}

TEST(ExternalDriver, TheModulesOwnMessageExplainsAFailedOpen) {
    EXPECT_THAT(
        [] {
            make_actuator("trace", {{"colour", "blue"}}, example_drivers());
        },
        ::testing::ThrowsMessage<DeviceError>(
            HasSubstr("trace: bad trace setting colour = \"blue\"")));
    EXPECT_THAT([] { make_actuator("trace", {}, example_drivers()); },
                ::testing::ThrowsMessage<DeviceError>(HasSubstr("path is required")));
    EXPECT_THAT(
        [] {
            make_actuator("trace", {{"path", "/nonexistent/dir/t.log"}}, example_drivers());
        },
        ::testing::ThrowsMessage<DeviceError>(
            HasSubstr("cannot open /nonexistent/dir/t.log: No such file or directory")));
}

TEST(ExternalDriver, ModulesThatAreNotDriversAreNamedAndLeftOut) {
    TempDir dir;
    dir.write("garbage.so", "not an ELF file");
    // Beside it, a copy of the example module: the one driver found.
    std::filesystem::copy_file(example_drivers() / "trace.so", dir.path() / "copy.so");
    EXPECT_THAT([&] { DriverModule::load(dir.path() / "garbage.so"); },
                ::testing::ThrowsMessage<std::runtime_error>(
                    HasSubstr((dir.path() / "garbage.so").string())));
    std::filesystem::permissions(dir.path(), std::filesystem::perms(0755));
    const auto found = scan_driver_modules(dir.path());
    ASSERT_EQ(found->modules().size(), 1u);
    EXPECT_EQ(found->modules()[0].path, dir.path() / "copy.so");
    ASSERT_EQ(found->refused().size(), 1u);
    EXPECT_EQ(found->refused()[0].path, dir.path() / "garbage.so");
    EXPECT_THAT([&] { make_actuator("nosuch", {}, dir.path()); },
                ::testing::ThrowsMessage<std::invalid_argument>(
                    HasSubstr("unknown driver \"nosuch\" (available: sim, evdev, gpio-erm, "
                              "gpio-lra, sysfs-pwm, led-vibrator, timed-output, trace)")));
}

TEST(ExternalDriver, ALibraryWithoutTheEntryPointIsRefused) {
    const std::filesystem::path libc = "/lib/x86_64-linux-gnu/libc.so.6";
    if (!std::filesystem::exists(libc)) {
        GTEST_SKIP() << libc << " is not there on this architecture";
    }
    EXPECT_THAT([&] { DriverModule::load(libc); },
                ::testing::ThrowsMessage<std::runtime_error>(
                    HasSubstr("has no vibscore_driver_entry symbol")));
}

TEST(CommonSettings, AreTakenOutAndCheckedForEveryDriver) {
    std::map<std::string, std::string> settings = {
        {"max-on-time-ms", "2000"}, {"pulse-period-ms", "25"}, {"model", "erm"}};
    const auto common = take_common_settings("sim", settings);
    EXPECT_EQ(common.max_on_time_s, 2.0);
    EXPECT_EQ(common.pulse_period_s, 0.025);
    EXPECT_EQ(settings.size(), 1u);  // the backend's own
    std::map<std::string, std::string> bad = {{"pulse-period-ms", "1"}};
    EXPECT_THAT([&] { take_common_settings("gpio-erm", bad); },
                ::testing::ThrowsMessage<std::invalid_argument>(
                    HasSubstr("gpio-erm setting pulse-period-ms = \"1\"")));
}

}  // namespace
}  // namespace vibscore::drivers
