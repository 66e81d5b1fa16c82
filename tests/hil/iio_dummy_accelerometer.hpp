#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace vibscore::hil {

// A real kernel IIO device: the kernel's IIO dummy driver (built by tests/hil/vm-prepare and
// patched there into a three-axis accelerometer: in_accel_{x,y,z}_raw = 34, in_accel_scale =
// 0.009807, a kfifo buffer whose scans carry x 344, y -20, z 1000 and the timestamp), created
// through configfs, with a sysfs trigger as its current trigger so that its buffer can be fed.
// Removed again on destruction.
class IioDummyAccelerometer {
  public:
    explicit IioDummyAccelerometer(const std::string& name = "vibscore-accel");
    ~IioDummyAccelerometer();
    IioDummyAccelerometer(const IioDummyAccelerometer&) = delete;
    IioDummyAccelerometer& operator=(const IioDummyAccelerometer&) = delete;

    const std::filesystem::path& folder() const {
        return folder_;
    }                                      // /sys/bus/iio/devices/iio:deviceN
    std::filesystem::path device() const;  // /dev/iio:deviceN

    // What the dummy reports, in m/s²: polled (every axis reads 34) and buffered.
    static constexpr double kScale = 0.009807;
    static constexpr int kPolledRaw = 34;
    static constexpr int kScanRaw[3] = {344, -20, 1000};

    // Fires the trigger (one scan into the buffer when it is enabled) every `period` from a
    // thread of its own, as a sensor's data-ready interrupt would, until stop_firing().
    void start_firing(std::chrono::microseconds period);
    // How many times it has fired.
    unsigned fired() const { return fired_; }
    // Stops firing; how many times it fired.
    unsigned stop_firing();

  private:
    std::filesystem::path config_;   // /sys/kernel/config/iio/devices/dummy/NAME
    std::filesystem::path folder_;   // /sys/bus/iio/devices/iio:deviceN
    std::filesystem::path trigger_;  // /sys/bus/iio/devices/triggerM (sysfstrigK)
    std::atomic<bool> firing_{false};
    std::atomic<unsigned> fired_{0};
    std::thread firer_;
};

}  // namespace vibscore::hil
