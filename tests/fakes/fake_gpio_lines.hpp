#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/monotonic_clock.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_lines.hpp"

namespace vibscore::testing {

// One set_values() call as the fake saw it.
struct GpioRecord {
    std::int64_t time_ns;  // CLOCK_MONOTONIC when the values were set
    std::vector<int> values;
    std::thread::id thread;
};

// A fake GPIO chip: the lines it hands out record every set_values() call with its time and can
// be made to fail. Shared between the test and the lines (which the actuator owns).
class FakeGpio : public std::enable_shared_from_this<FakeGpio> {
  public:
    // Lines `offsets` of `chip`; the values start low, as a real request leaves them.
    std::unique_ptr<drivers::GpioLines> lines(std::vector<unsigned> offsets,
                                              std::string chip = "gpiochip9");

    std::vector<GpioRecord> records() const {
        const std::lock_guard lock(mutex_);
        return records_;
    }

    // Waits (at most `limit`, only so that a broken program cannot hang the test) until
    // `done(records)` holds; returns whether it did.
    bool wait_until(const std::function<bool(const std::vector<GpioRecord>&)>& done,
                    std::chrono::seconds limit = std::chrono::seconds(20)) const {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, limit, [&] { return done(records_); });
    }
    bool wait_for_records(std::size_t count) const {
        return wait_until([count](const auto& records) { return records.size() >= count; });
    }
    bool wait_for_failures(std::size_t count) const {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, std::chrono::seconds(20),
                                 [&] { return failures_ >= count; });
    }

    // From now on every set_values() throws DeviceError (EIO), until heal().
    void fail() {
        const std::lock_guard lock(mutex_);
        failing_ = true;
    }
    void heal() {
        const std::lock_guard lock(mutex_);
        failing_ = false;
    }
    bool released() const {
        const std::lock_guard lock(mutex_);
        return released_;
    }

  private:
    class Lines;

    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    std::vector<GpioRecord> records_;
    bool failing_ = false;
    std::size_t failures_ = 0;
    bool released_ = false;
};

class FakeGpio::Lines final : public drivers::GpioLines {
  public:
    Lines(std::shared_ptr<FakeGpio> gpio, std::vector<unsigned> offsets, std::string chip)
        : gpio_(std::move(gpio)),
          count_(offsets.size()),
          description_(drivers::describe_lines(chip, offsets)) {}
    ~Lines() override {
        const std::lock_guard lock(gpio_->mutex_);
        gpio_->released_ = true;
        gpio_->changed_.notify_all();
    }

    std::size_t count() const override { return count_; }
    std::string describe() const override { return description_; }

    void set_values(const std::vector<int>& values) override {
        const std::int64_t now_ns = monotonic_now_ns();
        const std::lock_guard lock(gpio_->mutex_);
        if (values.size() != count_) {
            throw std::logic_error("set_values: " + std::to_string(values.size()) + " values for " +
                                   std::to_string(count_) + " lines");
        }
        if (gpio_->failing_) {
            ++gpio_->failures_;
            gpio_->changed_.notify_all();
            throw drivers::DeviceError(description_ + ": cannot set values: Input/output error");
        }
        std::vector<int> levels;
        for (const int value : values) {
            levels.push_back(value != 0 ? 1 : 0);
        }
        gpio_->records_.push_back({now_ns, std::move(levels), std::this_thread::get_id()});
        gpio_->changed_.notify_all();
    }

  private:
    std::shared_ptr<FakeGpio> gpio_;
    std::size_t count_;
    std::string description_;
};

inline std::unique_ptr<drivers::GpioLines> FakeGpio::lines(std::vector<unsigned> offsets,
                                                           std::string chip) {
    return std::make_unique<Lines>(shared_from_this(), std::move(offsets), std::move(chip));
}

inline bool all_low(const GpioRecord& record) {
    return std::all_of(record.values.begin(), record.values.end(), [](int v) { return v == 0; });
}

// Whether the last record set every line low.
inline bool ends_low(const std::vector<GpioRecord>& records) {
    return !records.empty() && all_low(records.back());
}

// Whether the last record set exactly `values`.
inline bool ends_with(const std::vector<GpioRecord>& records, const std::vector<int>& values) {
    return !records.empty() && records.back().values == values;
}

// The fraction of each period (rising edge to rising edge of `line`) that `line` was high, in
// order (the lines start low).
inline std::vector<double> period_duties(const std::vector<GpioRecord>& records, std::size_t line) {
    std::vector<double> duties;
    int previous = 0;
    std::int64_t rise = -1;
    std::int64_t fall = -1;
    for (const auto& record : records) {
        const int value = record.values[line];
        if (value == 1 && previous == 0) {
            if (rise >= 0 && fall >= rise) {
                duties.push_back(static_cast<double>(fall - rise) /
                                 static_cast<double>(record.time_ns - rise));
            }
            rise = record.time_ns;
        } else if (value == 0 && previous == 1) {
            fall = record.time_ns;
        }
        previous = value;
    }
    return duties;
}

// The median of the per-period duties: what the waveform was, not what a late wake-up made of
// one period. -1 when no whole period was recorded.
inline double median_duty(const std::vector<GpioRecord>& records, std::size_t line) {
    auto duties = period_duties(records, line);
    if (duties.empty()) {
        return -1.0;
    }
    std::nth_element(duties.begin(), duties.begin() + duties.size() / 2, duties.end());
    return duties[duties.size() / 2];
}

// When `line` went from low to high (the lines start low).
inline std::vector<std::int64_t> rise_times(const std::vector<GpioRecord>& records,
                                            std::size_t line) {
    std::vector<std::int64_t> times;
    int previous = 0;
    for (const auto& record : records) {
        if (record.values[line] == 1 && previous == 0) {
            times.push_back(record.time_ns);
        }
        previous = record.values[line];
    }
    return times;
}

inline std::size_t rising_edges(const std::vector<GpioRecord>& records, std::size_t line) {
    return rise_times(records, line).size();
}

}  // namespace vibscore::testing
