#pragma once

#include <filesystem>
#include <memory>

#include "daemon/sensors/accelerometer.hpp"
#include "daemon/sensors/sensor_io.hpp"

namespace vibscore::sensors {

// Whether an IIO device folder (/sys/bus/iio/devices/iio:deviceN) is an accelerometer: it has
// in_accel_x, _y and _z, raw or as scan elements.
bool is_iio_accelerometer(const std::filesystem::path& folder, SensorIo& io);

// The reader for an IIO accelerometer: buffered (the /dev/iio:deviceN character device, its
// scan_elements enabled for x, y, z and the timestamp on CLOCK_MONOTONIC, at the highest
// sampling frequency it offers up to 2 kHz) when it has a buffer, else polled (in_accel_*_raw x
// scale read at its sampling frequency, 400 Hz when it names none). Both put back what they
// changed (enables, sampling frequency, timestamp clock) when a recording ends. Throws
// std::runtime_error naming the folder when it is not an accelerometer or lacks a scale.
std::unique_ptr<Accelerometer> open_iio_accelerometer(const std::filesystem::path& folder,
                                                      const SensorRoots& roots,
                                                      std::shared_ptr<SensorIo> io);

}  // namespace vibscore::sensors
