// The GPIO character device end to end, without the daemon: a consumer speaking the kernel's
// uAPI v2 directly (gpio_uapi.hpp) drives lines of a gpio-sim chip, and the fixtures read back
// what the kernel was told. These check the fixtures the other GPIO tests rely on.
#include <gtest/gtest.h>

#include <thread>

#include "tests/hil/gpio_lines_sampler.hpp"
#include "tests/hil/gpio_sim_chip.hpp"
#include "tests/hil/gpio_uapi.hpp"
#include "tests/hil/gpio_value_trace.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

using Direction = GpioUapiLines::Direction;

TEST(GpioSmoke, ValuesDrivenThroughTheCharacterDeviceAreWhatTheChipSees) {
    GpioSimChip sim({4, "vibscore-hil-chip", {"motor", "in1", "in2"}});
    const auto chip = gpio_chip_info(sim.chip_path());
    EXPECT_EQ(chip.name, sim.chip_name());
    EXPECT_EQ(chip.label, "vibscore-hil-chip");
    EXPECT_EQ(chip.lines, 4u);
    EXPECT_EQ(gpio_line_info(sim.chip_path(), 0).name, "motor");
    EXPECT_EQ(gpio_line_info(sim.chip_path(), 3).name, "");

    GpioUapiLines motor(sim.chip_path(), {0}, Direction::output);
    EXPECT_EQ(sim.value(0), 0);
    motor.set_values({1});
    EXPECT_EQ(sim.value(0), 1);
    EXPECT_EQ(sim.value(1), 0);
    motor.set_values({0});
    EXPECT_EQ(sim.value(0), 0);

    GpioUapiLines in2(sim.chip_path(), {2}, Direction::output);
    in2.set_values({1});
    EXPECT_EQ(sim.value(2), 1);
    const auto info = gpio_line_info(sim.chip_path(), 2);
    EXPECT_TRUE(info.used);
    EXPECT_TRUE(info.output);
    EXPECT_FALSE(info.pull_down) << "requested without a bias";
    EXPECT_EQ(info.consumer, "vibscore-hil");
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 1).used);

    // A released line falls back to its pull.
    in2.release();
    EXPECT_FALSE(gpio_line_info(sim.chip_path(), 2).used);
    EXPECT_EQ(sim.value(2), 0);
    sim.set_pull(2, true);
    EXPECT_EQ(sim.value(2), 1);
}

TEST(GpioSmoke, AnInputLineReadsThePullTheTestSets) {
    GpioSimChip sim({2});
    GpioUapiLines line(sim.chip_path(), {1}, Direction::input);
    EXPECT_TRUE(gpio_line_info(sim.chip_path(), 1).input);
    EXPECT_EQ(line.values(), std::vector<int>{0});
    sim.set_pull(1, true);
    EXPECT_EQ(line.values(), std::vector<int>{1});
}

TEST(GpioSmoke, TheTraceRecordsEverySetOfTheChipsLinesInOrderAndNoOtherChips) {
    GpioSimChip sim({3});
    GpioSimChip other({1});
    GpioValueTrace trace(sim);
    GpioUapiLines lines(sim.chip_path(), {2, 0}, Direction::output);
    GpioUapiLines elsewhere(other.chip_path(), {0}, Direction::output);
    lines.set_values({1, 0});
    elsewhere.set_values({1});
    lines.set_values({0, 1});
    // The request's initial lows, then each set line by line.
    EXPECT_EQ(trace.sets(),
              (std::vector<GpioValueSet>{{2, 0}, {0, 0}, {2, 1}, {0, 0}, {2, 0}, {0, 1}}));
}

TEST(GpioSmoke, TheSamplerRecordsEveryEdgeOfALineInOrder) {
    GpioSimChip sim({1});
    GpioUapiLines line(sim.chip_path(), {0}, Direction::output);
    GpioLinesSampler sampler(sim, {0});
    // Each level is held until the sampler has seen it: no timing involved.
    for (int i = 0; i < 6; ++i) {
        const int value = (i + 1) % 2;
        line.set_values({value});
        vibscore::testing::wait_until(
            [&] { return sampler.changes().size() >= static_cast<std::size_t>(i) + 2; }, 5s, 1ms);
    }
    const auto transitions = sampler.changes();
    ASSERT_EQ(transitions.size(), 7u);
    for (std::size_t i = 0; i < transitions.size(); ++i) {
        EXPECT_EQ(transitions[i].values.at(0), static_cast<int>(i % 2)) << "transition " << i;
        EXPECT_LE(transitions[i].before, transitions[i].seen);
        if (i > 0) {
            EXPECT_LE(transitions[i - 1].seen, transitions[i].before);
        }
    }
}

TEST(GpioSmoke, TheSamplerMeasuresTheDutyCycleOfASoftwarePwm) {
    GpioSimChip sim({1});
    GpioUapiLines line(sim.chip_path(), {0}, Direction::output);
    GpioLinesSampler sampler(sim, {0});
    // Sampling steadily (the constructor returned at its first sample) before the first rise.
    ASSERT_TRUE(vibscore::testing::wait_until([&] { return sampler.samples() >= 2; }, 5s, 1ms));

    // 8 Hz at 33 %: the driver's own clock says how long the line was really high. Pulses are
    // long enough that the sampler cannot miss one even when TCG stalls it for a while.
    const auto begin = Clock::now();
    Clock::duration driven_high{0};
    for (int period = 0; period < 6; ++period) {
        line.set_values({1});
        const auto rise = Clock::now();
        vibscore::testing::pace_until(rise + 40ms);  // the software PWM under test: paced
        line.set_values({0});
        driven_high += Clock::now() - rise;
        vibscore::testing::pace_for(80ms);
    }
    const auto end = Clock::now();

    const auto measured = sampler.high_time(0, begin, end);
    const auto tolerance = std::max<Clock::duration>(10ms, driven_high / 5);
    EXPECT_NEAR(std::chrono::duration<double>(measured).count(),
                std::chrono::duration<double>(driven_high).count(),
                std::chrono::duration<double>(tolerance).count())
        << sampler.samples() << " samples";
    std::size_t rises = 0;
    for (const auto& transition : sampler.changes()) {
        rises += transition.values.at(0) == 1 ? 1 : 0;
    }
    EXPECT_EQ(rises, 6u);
}

}  // namespace
}  // namespace vibscore::hil
