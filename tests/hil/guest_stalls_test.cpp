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

}  // namespace
}  // namespace vibscore::hil
