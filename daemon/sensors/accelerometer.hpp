#pragma once

#include <cstdint>
#include <string>
#include <vector>

// The one seam between calibration and the accelerometers a device has (docs/drivers.md,
// "Calibrating"): IIO buffered, IIO polled, evdev, and the sim's model. Each records a window of
// time and hands over what it read; nothing else about the hardware leaks out.
namespace vibscore::sensors {

// One reading: when it was taken (CLOCK_MONOTONIC, nanoseconds) and the three axes in m/s²,
// gravity included, in the sensor's own orientation.
struct Reading {
    std::int64_t t_ns = 0;
    double x = 0.0, y = 0.0, z = 0.0;
};

// An accelerometer that can record a window. Used by one calibration at a time, from one thread
// (the calibration's), never the bus thread: start() and stop() may block for milliseconds.
class Accelerometer {
  public:
    virtual ~Accelerometer() = default;

    // For people and logs: what it is and how it is read ("/dev/iio:device0 (lsm6dsl), buffered,
    // 833 Hz").
    virtual std::string describe() const = 0;

    // Starts recording: readings are kept from now on. Throws std::runtime_error naming the
    // device and what failed (it went away, a sysfs write was refused).
    virtual void start() = 0;

    // Ends the recording and returns the readings since start(), in time order. The device is
    // left as it was found (buffer disabled, channels as before) even when it fails.
    virtual std::vector<Reading> stop() = 0;
};

}  // namespace vibscore::sensors
