#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vibscore::hil {

struct GpioSimOptions {
    unsigned lines = 4;
    std::string label;                    // the chip's label; empty: gpio-sim's own
    std::vector<std::string> line_names;  // names of lines 0.., may be shorter than `lines`
};

// A gpio-sim chip configured through configfs: a real /dev/gpiochipN that libgpiod can request
// lines of, whose driven values the test reads back. Removed again on destruction.
class GpioSimChip {
  public:
    explicit GpioSimChip(GpioSimOptions options = {});
    ~GpioSimChip();
    GpioSimChip(const GpioSimChip&) = delete;
    GpioSimChip& operator=(const GpioSimChip&) = delete;

    const std::filesystem::path& chip_path() const { return chip_path_; }  // /dev/gpiochipN
    const std::string& chip_name() const { return chip_name_; }            // gpiochipN
    unsigned lines() const { return lines_; }

    // The value a consumer drives on `line`; while no consumer holds it, the pull's value.
    int value(unsigned line) const;
    // What `line` reads as an input (and what it falls back to when released).
    void set_pull(unsigned line, bool up) const;
    // sim_gpioK/value in sysfs, for samplers.
    std::filesystem::path value_file(unsigned line) const;

  private:
    std::filesystem::path config_;  // /sys/kernel/config/gpio-sim/NAME
    std::filesystem::path sysfs_;   // /sys/devices/platform/gpio-sim.M/gpiochipN
    std::filesystem::path chip_path_;
    std::string chip_name_;
    unsigned lines_;
};

// One change of a sampled line: it happened after `before` and had happened at `seen`.
struct GpioTransition {
    std::chrono::steady_clock::time_point before;
    std::chrono::steady_clock::time_point seen;
    int value;
};

// Reads one line's value in its own thread every `period` and records the changes, for duty
// cycle and edge assertions. The first transition is the value found at the start (the
// constructor returns once it is recorded). Its
// resolution is the sampling interval actually achieved (a sysfs read under TCG costs tens of
// microseconds): good for on/off and duty cycles over many periods, not for edge timing.
class GpioLineSampler {
  public:
    GpioLineSampler(const GpioSimChip& chip, unsigned line,
                    std::chrono::microseconds period = std::chrono::microseconds(50));
    ~GpioLineSampler();
    GpioLineSampler(const GpioLineSampler&) = delete;
    GpioLineSampler& operator=(const GpioLineSampler&) = delete;

    std::vector<GpioTransition> transitions() const;
    std::uint64_t samples() const { return samples_; }
    // How long the line was high within [begin, end), by the `seen` times of its edges.
    std::chrono::nanoseconds high_time(std::chrono::steady_clock::time_point begin,
                                       std::chrono::steady_clock::time_point end) const;

  private:
    void run(const std::filesystem::path& file, std::chrono::microseconds period);
    void fail(int error);  // the sampling thread stops: it cannot read the file

    std::atomic<bool> stop_{false};
    std::atomic<std::uint64_t> samples_{0};
    mutable std::mutex mutex_;
    std::condition_variable first_sample_;
    int error_ = 0;
    std::vector<GpioTransition> transitions_;
    std::thread thread_;
};

}  // namespace vibscore::hil
