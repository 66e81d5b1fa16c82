#include "daemon/drivers/pwm_thread.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "tests/fakes/fake_gpio_lines.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::drivers {
namespace {

using ::testing::HasSubstr;
using vibscore::testing::all_low;
using vibscore::testing::ends_low;
using vibscore::testing::ends_with;
using vibscore::testing::FakeGpio;
using vibscore::testing::GpioRecord;

constexpr std::int64_t kMs = 1'000'000;

// Three distinct states per 3 ms period, so every edge shows up as a record.
PwmWaveform three_step() {
    return {3 * kMs, {{0, {1, 0}}, {1 * kMs, {0, 1}}, {2 * kMs, {0, 0}}}};
}

// Line 0 high for the first half of a 4 ms period.
PwmWaveform half_high(std::size_t line) {
    std::vector<int> high{0, 0};
    high[line] = 1;
    return {4 * kMs, {{0, high}, {2 * kMs, {0, 0}}}};
}

// Lets the thread run for a while: whatever it does meanwhile shows up in the records. Not a
// wait for something (nothing is expected to happen): the stretch is the time in which a wrong
// thread would write, 20 of its 3 ms periods.
void let_run() {
    vibscore::testing::pace_for(std::chrono::milliseconds(60));
}

class PwmThreadTest : public ::testing::Test {
  protected:
    std::shared_ptr<FakeGpio> gpio = std::make_shared<FakeGpio>();
    std::unique_ptr<PwmThread> thread =
        std::make_unique<PwmThread>(gpio->lines({17, 18}), /*rt_priority=*/0);
};

TEST_F(PwmThreadTest, WritesNothingBeforeTheFirstPlay) {
    let_run();
    EXPECT_TRUE(gpio->records().empty()) << "the lines were requested low; nothing to do";
    EXPECT_FALSE(thread->realtime());
}

TEST_F(PwmThreadTest, PlaysTheEdgesInOrderWithRisingDeadlines) {
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_records(30));
    const auto records = gpio->records();
    const std::vector<std::vector<int>> cycle{{1, 0}, {0, 1}, {0, 0}};
    for (std::size_t i = 0; i < records.size(); ++i) {
        EXPECT_EQ(records[i].values, cycle[i % 3]) << "record " << i;
        if (i > 0) {
            EXPECT_GE(records[i].time_ns, records[i - 1].time_ns);
        }
    }
}

TEST_F(PwmThreadTest, WritesFromItsOwnThreadOnly) {
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_records(6));
    thread->stop();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    for (const auto& record : gpio->records()) {
        EXPECT_NE(record.thread, std::this_thread::get_id());
    }
}

TEST_F(PwmThreadTest, SteadyOutputIsWrittenOnceAndCostsNoWakeUps) {
    thread->play({0, {{0, {1, 1}}}});
    ASSERT_TRUE(gpio->wait_for_records(1));
    let_run();
    const auto records = gpio->records();
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0].values, (std::vector<int>{1, 1}));
}

TEST_F(PwmThreadTest, StopDrivesEveryLineLowAndThenStaysQuiet) {
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_records(9));
    thread->stop();
    const std::size_t at_stop = gpio->records().size();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    let_run();
    const auto records = gpio->records();
    EXPECT_TRUE(all_low(records.back()));
    // At most the edge that was being written when stop() came, then low, then nothing.
    EXPECT_LE(records.size(), at_stop + 2);
}

TEST_F(PwmThreadTest, OffEndsAHighPulseAtItsEdgeAndStartsNoNewOne) {
    thread->play(half_high(0));
    ASSERT_TRUE(
        gpio->wait_until([](const auto& r) { return r.size() >= 3 && r.back().values[0]; }));
    thread->stop();
    const std::size_t at_stop = gpio->records().size();
    ASSERT_TRUE(gpio->wait_until(ends_low));
    let_run();
    const auto records = gpio->records();
    std::size_t rises_after_stop = 0;
    for (std::size_t i = at_stop; i < records.size(); ++i) {
        rises_after_stop += records[i].values[0];
    }
    // The one in flight at most; never one that began after the stop had been taken.
    EXPECT_LE(rises_after_stop, 1u);
}

TEST_F(PwmThreadTest, NewWaveformWaitsForThePeriodBoundary) {
    for (int change = 0; change < 20; ++change) {
        thread->play(three_step());
        ASSERT_TRUE(gpio->wait_until([](const auto& r) { return ends_with(r, {0, 1}); }));
        thread->play({3 * kMs, {{0, {1, 1}}, {1 * kMs, {0, 0}}}});
        ASSERT_TRUE(gpio->wait_until([](const auto& r) { return ends_with(r, {1, 1}); }));
    }
    const auto records = gpio->records();
    for (std::size_t i = 1; i < records.size(); ++i) {
        // The three steps always run to their end: no period is cut short by the change.
        if (records[i].values == std::vector<int>{1, 1}) {
            EXPECT_EQ(records[i - 1].values, (std::vector<int>{0, 0})) << "record " << i;
        }
    }
}

TEST_F(PwmThreadTest, ALineErrorIsReportedOnceAndTheThreadGoesOn) {
    gpio->fail();
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_failures(1));
    std::optional<std::string> error;
    ASSERT_TRUE(
        vibscore::testing::wait_until([&] { return (error = thread->take_error()).has_value(); }));
    EXPECT_THAT(*error, HasSubstr("gpiochip9 lines 17, 18"));
    EXPECT_THAT(*error, HasSubstr("Input/output error"));
    EXPECT_FALSE(thread->take_error()) << "one error, reported once";

    gpio->heal();
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_records(6));
    EXPECT_FALSE(thread->take_error());
}

TEST_F(PwmThreadTest, DestructionDrivesEveryLineLow) {
    thread->play({0, {{0, {1, 0}}}});
    ASSERT_TRUE(gpio->wait_for_records(1));
    thread.reset();
    const auto records = gpio->records();
    ASSERT_EQ(records.size(), 2u);
    EXPECT_TRUE(all_low(records.back()));
    EXPECT_TRUE(gpio->released());
}

TEST_F(PwmThreadTest, DestructionWhilePlayingEndsLow) {
    thread->play(three_step());
    ASSERT_TRUE(gpio->wait_for_records(4));
    thread.reset();
    EXPECT_TRUE(all_low(gpio->records().back()));
}

}  // namespace
}  // namespace vibscore::drivers
