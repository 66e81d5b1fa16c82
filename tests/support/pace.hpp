#pragma once

#include <chrono>
#include <thread>

// The one place a test lets time pass on purpose. Waiting for something to happen is never
// this: that is wait_until (tests/support/wait_until.hpp), whose time is only a bound. These are
// for time that is itself the subject: a simulated device's period (samples a second, a line
// toggled at a rate), a stretch of input as long as the thing under test must measure, a
// deadline the product is tested against, or the random jitter of a race being provoked. The
// unit suite's no_fixed_sleeps check refuses any other sleep in tests/, so every such pause
// can be found by this name.
namespace vibscore::testing {

// Lets `duration` pass: time the test is about, not a wait for an event.
inline void pace_for(std::chrono::nanoseconds duration) {
    std::this_thread::sleep_for(duration);
}

// Lets time pass until `when` (a period kept against drift): time the test is about.
inline void pace_until(std::chrono::steady_clock::time_point when) {
    std::this_thread::sleep_until(when);
}

}  // namespace vibscore::testing
