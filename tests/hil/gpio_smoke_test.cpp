// The GPIO character device end to end, without the daemon: libgpiod (v1 C++ API) drives
// lines of a gpio-sim chip and the GpioSimChip fixture reads back what the kernel was told.
#include <gtest/gtest.h>

#include <gpiod.hpp>
#include <thread>

#include "tests/hil/gpio_lines_sampler.hpp"
#include "tests/hil/gpio_sim_chip.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

gpiod::line output_line(gpiod::chip& chip, const std::string& name) {
    auto line = chip.find_line(name);
    line.request({"vibscore-hil", gpiod::line_request::DIRECTION_OUTPUT, 0}, 0);
    return line;
}

TEST(GpioSmoke, ValuesDrivenThroughLibgpiodAreWhatTheChipSees) {
    GpioSimChip sim({4, "vibscore-hil-chip", {"motor", "in1", "in2"}});
    gpiod::chip chip(sim.chip_path().string(), gpiod::chip::OPEN_BY_PATH);
    EXPECT_EQ(chip.label(), "vibscore-hil-chip");
    EXPECT_EQ(chip.num_lines(), 4u);

    auto motor = output_line(chip, "motor");
    EXPECT_EQ(motor.offset(), 0u);
    EXPECT_EQ(sim.value(0), 0);
    motor.set_value(1);
    EXPECT_EQ(sim.value(0), 1);
    EXPECT_EQ(sim.value(1), 0);
    motor.set_value(0);
    EXPECT_EQ(sim.value(0), 0);

    auto in2 = output_line(chip, "in2");
    in2.set_value(1);
    EXPECT_EQ(sim.value(2), 1);
    EXPECT_TRUE(in2.is_used());
    EXPECT_EQ(in2.consumer(), "vibscore-hil");

    // A released line falls back to its pull.
    in2.release();
    EXPECT_EQ(sim.value(2), 0);
    sim.set_pull(2, true);
    EXPECT_EQ(sim.value(2), 1);
}

TEST(GpioSmoke, AnInputLineReadsThePullTheTestSets) {
    GpioSimChip sim({2});
    gpiod::chip chip(sim.chip_path().string(), gpiod::chip::OPEN_BY_PATH);
    auto line = chip.get_line(1);
    line.request({"vibscore-hil", gpiod::line_request::DIRECTION_INPUT, 0});
    EXPECT_EQ(line.get_value(), 0);
    sim.set_pull(1, true);
    EXPECT_EQ(line.get_value(), 1);
}

TEST(GpioSmoke, TheSamplerRecordsEveryEdgeOfALineInOrder) {
    GpioSimChip sim({1});
    gpiod::chip chip(sim.chip_path().string(), gpiod::chip::OPEN_BY_PATH);
    auto line = chip.get_line(0);
    line.request({"vibscore-hil", gpiod::line_request::DIRECTION_OUTPUT, 0}, 0);
    GpioLinesSampler sampler(sim, {0});
    // Each level is held until the sampler has seen it: no timing involved.
    for (int i = 0; i < 6; ++i) {
        const int value = (i + 1) % 2;
        line.set_value(value);
        const auto deadline = Clock::now() + 5s;
        while (sampler.changes().size() < static_cast<std::size_t>(i) + 2 &&
               Clock::now() < deadline) {
            std::this_thread::sleep_for(1ms);
        }
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
    gpiod::chip chip(sim.chip_path().string(), gpiod::chip::OPEN_BY_PATH);
    auto line = chip.get_line(0);
    line.request({"vibscore-hil", gpiod::line_request::DIRECTION_OUTPUT, 0}, 0);
    GpioLinesSampler sampler(sim, {0});
    std::this_thread::sleep_for(5ms);

    // 8 Hz at 33 %: the driver's own clock says how long the line was really high. Pulses are
    // long enough that the sampler cannot miss one even when TCG stalls it for a while.
    const auto begin = Clock::now();
    Clock::duration driven_high{0};
    for (int period = 0; period < 6; ++period) {
        line.set_value(1);
        const auto rise = Clock::now();
        std::this_thread::sleep_until(rise + 40ms);
        line.set_value(0);
        driven_high += Clock::now() - rise;
        std::this_thread::sleep_for(80ms);
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
