// open_gpio_lines() on gpio-sim: the libgpiod generation this build found (gpio_lines_v1.cpp on
// Debian 12, gpio_lines_v2.cpp on Debian 13) against the kernel's GPIO character device. What
// the kernel holds is read back through its uAPI v2 directly (gpio_uapi.hpp), the values it set
// through its trace (gpio_value_trace.hpp): the same assertions hold for both generations.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <iostream>
#include <string>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_lines.hpp"
#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/gpio_uapi.hpp"
#include "tests/hil/gpio_value_trace.hpp"

namespace vibscore::hil {
namespace {

using drivers::DeviceError;
using drivers::open_gpio_lines;
using ::testing::HasSubstr;

// The DeviceError's message for opening `offsets` on `chip` (fails the test when it opens).
std::string refusal(const std::string& chip, const std::vector<unsigned>& offsets) {
    try {
        open_gpio_lines(chip, offsets);
    } catch (const DeviceError& error) {
        return error.what();
    }
    ADD_FAILURE() << chip << " opened";
    return "";
}

TEST(GpioLines, RunWithTheLibgpiodTheBuildFound) {
    // The library loaded at run time is the one meson compiled against (on Debian 13 the test
    // runs in its root, with its libgpiod 2).
    EXPECT_EQ(drivers::gpio_library(), "libgpiod " VIBSCORE_GPIOD_VERSION);
    std::cout << "GPIO through " << drivers::gpio_library() << "\n";
}

TEST(GpioLines, AreOutputsForVibscoredWithThePullDownBiasDrivenLowFromTheStart) {
    GpioSimChip sim({4});
    // Pulled up: a line left to its pull would read 1.
    sim.set_pull(0, true);
    sim.set_pull(2, true);
    const auto lines = open_gpio_lines(sim.chip_name(), {0, 2});
    EXPECT_EQ(lines->count(), 2u);
    EXPECT_EQ(lines->describe(), sim.chip_name() + " lines 0, 2");
    for (const unsigned line : {0u, 2u}) {
        SCOPED_TRACE("line " + std::to_string(line));
        EXPECT_EQ(sim.value(line), 0);
        const auto info = gpio_line_info(sim.chip_path(), line);
        EXPECT_TRUE(info.used);
        EXPECT_EQ(info.consumer, "vibscored");
        EXPECT_TRUE(info.output);
        EXPECT_FALSE(info.input);
        EXPECT_TRUE(info.pull_down);
        EXPECT_FALSE(info.pull_up);
        EXPECT_FALSE(info.bias_disabled);
        EXPECT_FALSE(info.active_low);
        EXPECT_FALSE(info.open_drain);
        EXPECT_FALSE(info.open_source);
    }
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 1).used);
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 3).used);
}

TEST(GpioLines, SetTheirValuesTogetherInRequestOrder) {
    GpioSimChip sim({4});
    const auto lines = open_gpio_lines(sim.chip_path().string(), {3, 1});
    lines->set_values({1, 0});
    EXPECT_EQ(sim.value(3), 1);
    EXPECT_EQ(sim.value(1), 0);
    lines->set_values({0, 1});
    EXPECT_EQ(sim.value(3), 0);
    EXPECT_EQ(sim.value(1), 1);
    lines->set_values({5, 1});  // anything but 0 is high
    EXPECT_EQ(sim.value(3), 1);
    EXPECT_EQ(sim.value(1), 1);
    EXPECT_EQ(sim.value(0), 0);
    EXPECT_EQ(sim.value(2), 0);
}

TEST(GpioLines, AreDrivenLowAtTheRequestAndAgainBeforeTheRelease) {
    GpioSimChip sim({2});
    GpioValueTrace trace(sim);
    auto lines = open_gpio_lines(sim.chip_name(), {0, 1});
    lines->set_values({1, 1});
    // Pulled up from now on: once released, the lines read 1 whatever the last set was, so only
    // the trace can tell whether they were driven low first.
    sim.set_pull(0, true);
    sim.set_pull(1, true);
    lines.reset();
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 0).used);
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 1).used);
    EXPECT_EQ(trace.sets(),
              (std::vector<GpioValueSet>{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}, {1, 0}}));
}

TEST(GpioLines, FallLowThroughThePullDownBiasWhenTheKernelReleasesThem) {
    GpioSimChip sim({2});
    sim.set_pull(0, true);
    sim.set_pull(1, true);
    {
        // Released without a bias of its own, a line takes the pull it had: 1.
        GpioUapiLines other(sim.chip_path(), {1}, GpioUapiLines::Direction::output);
    }
    EXPECT_EQ(sim.value(1), 1);
    // vibscored's request set the pull-down bias, which the line keeps once released: it falls
    // low even with the last value driven high (the case of a SIGKILL, where nobody drives it
    // low: daemon_sigkill_test).
    {
        auto lines = open_gpio_lines(sim.chip_name(), {0});
        lines->set_values({1});
        EXPECT_EQ(sim.value(0), 1);
    }
    EXPECT_EQ(sim.value(0), 0);
}

TEST(GpioLines, FindTheChipByNamePathLabelOrNumber) {
    GpioSimChip sim({2, "vibscore-hil-lines-" + std::to_string(::getpid())});
    const std::string label = gpio_chip_info(sim.chip_path()).label;
    const std::string number = sim.chip_name().substr(std::string("gpiochip").size());
    for (const std::string& chip : {sim.chip_name(), sim.chip_path().string(), label, number}) {
        SCOPED_TRACE("chip = " + chip);
        const auto lines = open_gpio_lines(chip, {1});
        EXPECT_EQ(lines->describe(), chip + " line 1");
        lines->set_values({1});
        EXPECT_EQ(sim.value(1), 1);
        EXPECT_EQ(gpio_line_info(sim.chip_path(), 1).consumer, "vibscored");
    }
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 1).used);
}

TEST(GpioLines, AChipThatIsNotThereIsADeviceErrorNamingTheChipsThatAre) {
    GpioSimChip sim({2, "vibscore-hil-present"});
    const auto message = refusal("vibscore-hil-absent", {0});
    EXPECT_THAT(message, HasSubstr("GPIO chip vibscore-hil-absent: no such chip: no "
                                   "/dev/vibscore-hil-absent and no chip labelled "
                                   "\"vibscore-hil-absent\" (the chips are "));
    EXPECT_THAT(message, HasSubstr(sim.chip_name() + " \"vibscore-hil-present\""));
    EXPECT_EQ(refusal("/dev/gpiochip999", {0}),
              "GPIO chip /dev/gpiochip999: cannot open /dev/gpiochip999: No such file or "
              "directory");
    EXPECT_EQ(refusal("999", {0}),
              "GPIO chip 999: cannot open /dev/gpiochip999: No such file or directory");
    EXPECT_THAT(refusal("/dev/null", {0}),
                HasSubstr("GPIO chip /dev/null: cannot open /dev/null: not a GPIO chip"));
}

TEST(GpioLines, TheLastLineOfTheChipIsRequestedAndOneMoreIsADeviceError) {
    GpioSimChip sim({4});
    EXPECT_NO_THROW(open_gpio_lines(sim.chip_name(), {3}));
    EXPECT_EQ(refusal(sim.chip_name(), {0, 4}), sim.chip_name() + " line 4: no such line: " +
                                                    sim.chip_path().string() + " has lines 0 to 3");
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 0).used) << "nothing is left requested";
}

TEST(GpioLines, ALineAnotherConsumerHoldsIsBusyAndTheMessageNamesIt) {
    GpioSimChip sim({4});
    {
        GpioUapiLines other(sim.chip_path(), {2}, GpioUapiLines::Direction::input, "other-app");
        EXPECT_EQ(refusal(sim.chip_name(), {1, 2}),
                  sim.chip_name() +
                      " lines 1, 2: cannot request as output: busy: line 2 is "
                      "used by \"other-app\" (see gpioinfo)");
        EXPECT_FALSE(gpio_line_info(sim.chip_path(), 1).used) << "line 1 is not left requested";
    }
    // Released by the other consumer, the same lines are granted.
    EXPECT_NO_THROW(open_gpio_lines(sim.chip_name(), {1, 2}));
}

TEST(GpioLines, ALineVibscoredHoldsAlreadyIsBusy) {
    GpioSimChip sim({2});
    const auto lines = open_gpio_lines(sim.chip_name(), {0});
    EXPECT_EQ(refusal(sim.chip_name(), {0}),
              sim.chip_name() +
                  " line 0: cannot request as output: busy: line 0 is used by \"vibscored\" "
                  "(see gpioinfo)");
}

}  // namespace
}  // namespace vibscore::hil
