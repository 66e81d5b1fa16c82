#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <vector>

namespace vibscore::hil {

// A channel's state as the PWM core last applied it to pwm-sim (tests/hil/pwm-sim).
struct PwmChannelState {
    bool requested = false;  // exported to sysfs or held by a kernel consumer
    bool enabled = false;
    std::uint64_t period_ns = 0;
    std::uint64_t duty_cycle_ns = 0;
    bool inversed = false;
    std::uint64_t applies = 0;  // how many times the core applied a state
};

// One apply call, as pwm-sim logged it.
struct PwmApplied {
    std::chrono::steady_clock::time_point time;  // kernel CLOCK_MONOTONIC
    unsigned channel = 0;
    bool enabled = false;
    std::uint64_t period_ns = 0;
    std::uint64_t duty_cycle_ns = 0;
    bool inversed = false;
};

std::ostream& operator<<(std::ostream& out, const PwmApplied& applied);

// The pwm-sim chip loaded in the guest: /sys/class/pwm/pwmchipN is the real kernel PWM sysfs
// interface, and this reads back what the chip was told (from /sys/kernel/debug/pwm-sim). The
// log is emptied on construction; every channel still exported is unexported on destruction.
class PwmSimChip {
  public:
    PwmSimChip();
    ~PwmSimChip();
    PwmSimChip(const PwmSimChip&) = delete;
    PwmSimChip& operator=(const PwmSimChip&) = delete;

    const std::filesystem::path& sysfs_dir() const {
        return sysfs_dir_;
    }  // /sys/class/pwm/pwmchipN
    unsigned channels() const { return channels_; }

    PwmChannelState state(unsigned channel) const;
    std::vector<PwmApplied> log() const;
    void clear_log() const;

  private:
    std::filesystem::path sysfs_dir_;
    unsigned channels_ = 0;
};

}  // namespace vibscore::hil
