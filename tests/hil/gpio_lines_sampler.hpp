#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "tests/hil/gpio_sim_chip.hpp"

namespace vibscore::hil {

// A state of several lines that held all at once, and when it was first seen: after `before`,
// by `seen`.
struct LinesState {
    std::chrono::steady_clock::time_point before;
    std::chrono::steady_clock::time_point seen;
    std::vector<int> values;  // in the order the lines were given
};

// Samples several lines of a gpio-sim chip together, for assertions on how they relate (an
// H-bridge's inputs never both high, a motor line never high without its enable line). Each
// sample reads every line twice, in order, and is kept only when both rounds agree: every
// line then held its value over an interval that contains the end of the first round, so the
// values held together at that instant. (A line changing twice between its two reads would
// escape this; at the millisecond periods tested here it cannot.) Records each change of the
// whole state; the first is the state found at the start (the constructor returns once it is
// recorded). Its resolution is the sampling interval actually achieved (a sysfs read under TCG
// costs tens of microseconds): good for on/off and duty cycles over many periods, not for
// edge timing.
class GpioLinesSampler {
  public:
    GpioLinesSampler(const GpioSimChip& chip, std::vector<unsigned> lines,
                     std::chrono::microseconds period = std::chrono::microseconds(50));
    ~GpioLinesSampler();
    GpioLinesSampler(const GpioLinesSampler&) = delete;
    GpioLinesSampler& operator=(const GpioLinesSampler&) = delete;

    std::vector<LinesState> changes() const;
    std::uint64_t samples() const { return samples_; }
    // How long line `index` (in the order given) was high within [begin, end), by the `seen`
    // times of its changes.
    std::chrono::nanoseconds high_time(std::size_t index,
                                       std::chrono::steady_clock::time_point begin,
                                       std::chrono::steady_clock::time_point end) const;
    // Samples thrown away because a line changed while they were read.
    std::uint64_t torn_samples() const { return torn_; }

  private:
    void run(const std::vector<std::filesystem::path>& files, std::chrono::microseconds period);
    void fail(int error);

    std::atomic<bool> stop_{false};
    std::atomic<std::uint64_t> samples_{0};
    std::atomic<std::uint64_t> torn_{0};
    mutable std::mutex mutex_;
    std::condition_variable first_sample_;
    int error_ = 0;
    std::vector<LinesState> changes_;
    std::thread thread_;
};

}  // namespace vibscore::hil
