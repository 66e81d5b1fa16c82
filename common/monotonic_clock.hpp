#pragma once

#include <cstdint>

namespace vibscore {

// CLOCK_MONOTONIC, the clock every deadline is measured on: the daemon's timers, the player's
// cues, the PWM thread's edges, the simulated actuator's trace and the kernel's evdev stamps
// the editor's long presses are timed by.
std::int64_t monotonic_now_ns();

// The same clock in microseconds, sd-event's unit.
std::uint64_t monotonic_now_us();

}  // namespace vibscore
