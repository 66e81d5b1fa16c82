#include "tests/hil/guest_stalls.hpp"

#include <algorithm>

#include "tests/support/pace.hpp"

namespace vibscore::hil {

GuestStallMeter::GuestStallMeter(std::chrono::microseconds period)
    : thread_([this, period] { run(period); }) {}

GuestStallMeter::~GuestStallMeter() {
    stop_ = true;
    thread_.join();
}

double GuestStallMeter::worst_s() const {
    return static_cast<double>(worst_ns_.load()) * 1e-9;
}

std::vector<GuestStallMeter::Stall> GuestStallMeter::stalls() const {
    const std::lock_guard reading(stalls_lock_);
    return stalls_;
}

void GuestStallMeter::run(std::chrono::microseconds period) {
    auto due = std::chrono::steady_clock::now();
    while (!stop_) {
        due += period;
        // The period is the instrument's own rate, not a wait for anything.
        vibscore::testing::pace_until(due);
        { const std::lock_guard not_while_held(held_); }
        const auto now = std::chrono::steady_clock::now();
        const auto late = std::chrono::duration_cast<std::chrono::nanoseconds>(now - due).count();
        if (late > worst_ns_.load()) {
            worst_ns_ = late;
        }
        if (late > std::chrono::nanoseconds(period).count()) {
            const std::lock_guard writing(stalls_lock_);
            stalls_.push_back({now, std::chrono::nanoseconds(late)});
        }
        ++wakes_;
        // After a stall, measure from now: one stall is one lateness, not a backlog of them.
        due = std::max(due, now - period);
    }
}

double stalled_s(const std::vector<GuestStallMeter::Stall>& stalls,
                 GuestStallMeter::Clock::time_point from, GuestStallMeter::Clock::time_point to) {
    std::chrono::nanoseconds stopped{0};
    for (const auto& stall : stalls) {
        const auto begin = std::max(stall.woke - stall.late, from);
        const auto end = std::min(stall.woke, to);
        if (end > begin) {
            stopped += end - begin;
        }
    }
    return std::chrono::duration<double>(stopped).count();
}

}  // namespace vibscore::hil
