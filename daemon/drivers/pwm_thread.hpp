#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daemon/drivers/gpio_lines.hpp"

namespace vibscore::drivers {

// One change of the lines within a period: at `at_ns` after the period start, set `values`.
struct PwmEdge {
    std::int64_t at_ns = 0;
    std::vector<int> values;
    bool operator==(const PwmEdge&) const = default;
};

// A periodic pattern of line values. Edges are in time order within [0, period_ns). With fewer
// than two edges the output is steady: the single edge's values, or every line low when there
// is none (off).
struct PwmWaveform {
    std::int64_t period_ns = 0;
    std::vector<PwmEdge> edges;

    bool steady() const { return edges.size() < 2; }
    bool operator==(const PwmWaveform&) const = default;
};

// Plays PwmWaveforms on GpioLines from its own thread, which sleeps with clock_nanosleep to
// absolute CLOCK_MONOTONIC edge deadlines (period starts advance by exactly one period, so
// there is no drift). play() and stop() only hand the waveform over and return at once:
//  - from a steady output (off included) a waveform starts at once;
//  - a waveform replaces a running one at the next period start, so no pulse is cut short or
//    stretched;
//  - a steady output (off included) replaces a running waveform at its next edge: a high pulse
//    ends on time and no new one begins.
// A steady output costs no wake-ups. When the thread falls more than a period behind (it was
// not scheduled), it skips the missed periods instead of playing them late in a burst.
class PwmThread {
  public:
    // Takes the lines, which are low. rt_priority 1..99 asks for SCHED_FIFO at that priority
    // (without the privilege: one warning per process, and normal scheduling); 0 never asks.
    PwmThread(std::unique_ptr<GpioLines> lines, int rt_priority);
    // Stops the thread (at most one edge interval later) and drives every line low.
    ~PwmThread();
    PwmThread(const PwmThread&) = delete;
    PwmThread& operator=(const PwmThread&) = delete;

    void play(PwmWaveform waveform);
    // Every line low, then no wake-ups until the next play().
    void stop() { play({}); }

    // The message of the first line error since the last call, if any. After an error the
    // thread has tried to drive every line low and waits for the next play().
    std::optional<std::string> take_error();

    bool realtime() const { return realtime_; }

  private:
    void run();
    // Sets the lines unless they already hold `values`; false (error recorded) on failure.
    bool write(std::unique_lock<std::mutex>& lock, const std::vector<int>& values);
    void fail(std::unique_lock<std::mutex>& lock, const std::string& message);
    bool set_realtime(int priority);

    std::unique_ptr<GpioLines> lines_;
    const std::vector<int> all_low_;
    std::vector<int> written_;  // what the lines hold; empty when unknown (after an error)

    std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<PwmWaveform> pending_;  // guarded by mutex_
    std::optional<std::string> error_;    // guarded by mutex_
    bool quit_ = false;                   // guarded by mutex_

    bool realtime_ = false;
    std::thread thread_;
};

}  // namespace vibscore::drivers
