// The stall meter the daemon-level timing tests widen their tolerance by: it must see a stall
// as long as the one it went through, so that a tolerance is never widened by less than the
// guest was stopped.
#include <gtest/gtest.h>

#include "tests/hil/guest_stalls.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;

TEST(GuestStallMeter, ReportsAStallAtLeastAsLongAsTheOneItWasHeldThrough) {
    GuestStallMeter meter;
    ASSERT_TRUE(testing::wait_until([&] { return meter.wakes() >= 5; }));
    std::uint64_t wakes = 0;
    {
        const auto held = meter.hold();
        wakes = meter.wakes();
        // The stall's length is what this test is about.
        testing::pace_for(60ms);
        // Held, it wakes at most once more (one already past the hold when it was taken).
        EXPECT_LE(meter.wakes(), wakes + 1);
    }
    ASSERT_TRUE(testing::wait_until([&] { return meter.wakes() > wakes + 2; }));
    // Its next wake-up was due at most a period after the hold began.
    EXPECT_GE(meter.worst_s(), 0.060 - 0.001 - 0.0005);
}

TEST(GuestStallMeter, KeepsEveryStallSoTwoHoldsAddUpBeyondTheLongest) {
    GuestStallMeter meter;
    ASSERT_TRUE(testing::wait_until([&] { return meter.wakes() >= 5; }));
    const auto begin = GuestStallMeter::Clock::now();
    for (int hold = 0; hold < 2; ++hold) {
        const auto wakes = meter.wakes();
        {
            const auto held = meter.hold();
            // The stall's length is what this test is about.
            testing::pace_for(30ms);
        }
        ASSERT_TRUE(testing::wait_until([&] { return meter.wakes() > wakes + 2; }));
    }
    const auto end = GuestStallMeter::Clock::now();
    const auto stalls = meter.stalls();
    ASSERT_GE(stalls.size(), 2u);
    // Both holds, not only the longer (a guest under TCG may add stalls of its own: at least).
    EXPECT_GE(stalled_s(stalls, begin, end), 2 * (0.030 - 0.0015));
}

using Stall = GuestStallMeter::Stall;

TEST(StalledSeconds, CountsOnlyThePartsOfStallsInsideTheWindow) {
    const auto t0 = GuestStallMeter::Clock::time_point{} + 10s;
    // Stopped from t0 + 10 ms to t0 + 30 ms, and from t0 + 50 ms to t0 + 60 ms.
    const std::vector<Stall> stalls{{t0 + 30ms, 20ms}, {t0 + 60ms, 10ms}};
    EXPECT_NEAR(stalled_s(stalls, t0, t0 + 100ms), 0.030, 1e-12);
    // A window that cuts a stall counts the part inside it.
    EXPECT_NEAR(stalled_s(stalls, t0 + 20ms, t0 + 55ms), 0.015, 1e-12);
    // A stall that ends where the window begins, or begins where it ends, counts nothing.
    EXPECT_EQ(stalled_s(stalls, t0 + 30ms, t0 + 50ms), 0.0);
    EXPECT_NEAR(stalled_s(stalls, t0 + 29ms, t0 + 51ms), 0.002, 1e-12);
    // A window wholly inside a stall is all stopped.
    EXPECT_NEAR(stalled_s(stalls, t0 + 12ms, t0 + 18ms), 0.006, 1e-12);
    EXPECT_EQ(stalled_s({}, t0, t0 + 1s), 0.0);
}

}  // namespace
}  // namespace vibscore::hil
