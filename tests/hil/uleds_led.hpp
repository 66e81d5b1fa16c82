#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"
#include "tests/hil/fd_service_thread.hpp"

namespace vibscore::hil {

struct BrightnessChange {
    std::chrono::steady_clock::time_point time;  // when the fixture read it (CLOCK_MONOTONIC)
    int brightness;
};

// An LED class device made with /dev/uleds (the uleds module): a real /sys/class/leds/NAME
// with the kernel's triggers (ledtrig-transient is loaded in the guest), standing in for an LED
// driver whose brightness this records. Removed on destruction.
class UledsLed {
  public:
    explicit UledsLed(const std::string& name = "vibrator", int max_brightness = 255);
    ~UledsLed();
    UledsLed(const UledsLed&) = delete;
    UledsLed& operator=(const UledsLed&) = delete;

    const std::filesystem::path& sysfs_dir() const { return sysfs_dir_; }  // /sys/class/leds/NAME

    // Brightness as the kernel set it, in order; uleds keeps only the latest value between two
    // reads, so changes faster than the reading thread can be merged.
    std::vector<BrightnessChange> changes() const;
    void clear_changes();
    // Waits until a recorded change matches `match`; false after `timeout`.
    bool wait_for(const std::function<bool(const BrightnessChange&)>& match,
                  std::chrono::milliseconds timeout = std::chrono::seconds(5)) const;

  private:
    void service();  // runs on the service thread

    UniqueFd uleds_;
    std::filesystem::path sysfs_dir_;
    mutable std::mutex mutex_;  // guards what follows
    mutable std::condition_variable changed_;
    std::vector<BrightnessChange> changes_;
    std::unique_ptr<FdServiceThread> thread_;  // last: stops before the rest goes
};

}  // namespace vibscore::hil
