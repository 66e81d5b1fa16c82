#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace vibscore::hil {

// How late the guest wakes a thread that asks to run every `period`, worst case, while this
// lives. Under TCG the emulated CPU stops for tens of milliseconds whenever the host is busy,
// and then every thread in the guest is late by as much: the daemon's playback and the
// fixture that watches it alike. A timing assertion widens its tolerance by what this saw in
// the same window (onset_tolerance_s), so it still fails for a daemon late on its own account
// and not for a guest that was not running.
class GuestStallMeter {
  public:
    using Clock = std::chrono::steady_clock;
    // A wake-up that came more than a period after its time: the thread, and with it the
    // guest, did not run from `woke - late` to `woke`.
    struct Stall {
        Clock::time_point woke;
        std::chrono::nanoseconds late;
    };

    explicit GuestStallMeter(std::chrono::microseconds period = std::chrono::milliseconds(1));
    ~GuestStallMeter();
    GuestStallMeter(const GuestStallMeter&) = delete;
    GuestStallMeter& operator=(const GuestStallMeter&) = delete;

    // The longest a wake-up has come after its time so far, in seconds.
    double worst_s() const;
    std::uint64_t wakes() const { return wakes_; }
    // Every stall so far, in time order.
    std::vector<Stall> stalls() const;
    // Holds the meter's thread at its next wake-up until the lock goes, as a stalled guest
    // would: how its own test makes a stall of a known length.
    [[nodiscard]] std::unique_lock<std::mutex> hold() { return std::unique_lock(held_); }

  private:
    void run(std::chrono::microseconds period);

    std::atomic<bool> stop_{false};
    std::atomic<std::int64_t> worst_ns_{0};
    std::atomic<std::uint64_t> wakes_{0};
    mutable std::mutex stalls_lock_;
    std::vector<Stall> stalls_;
    std::mutex held_;
    std::thread thread_;  // last: starts once the rest is there
};

// How long `stalls` kept the guest stopped between `from` and `to`, in seconds: the parts of
// every stall inside that window, added up. A stretch of work that takes many of the guest's
// timeslices is late by all of its stalls, not only by the longest.
double stalled_s(const std::vector<GuestStallMeter::Stall>& stalls,
                 GuestStallMeter::Clock::time_point from, GuestStallMeter::Clock::time_point to);

}  // namespace vibscore::hil
