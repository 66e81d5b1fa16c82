#pragma once

#include <memory>
#include <string>

#include "daemon/sensors/accelerometer.hpp"
#include "daemon/sensors/sensor_io.hpp"

namespace vibscore::sensors {

// [calibration] accelerometer = auto | PATH (docs/drivers.md, "Calibrating").
//   auto: the first IIO device under roots.iio_devices with in_accel channels, else the first
//         evdev accelerometer in roots.dev/input, else `backend_own` (the sim's); nullptr when
//         there is none of them.
//   PATH: an IIO device's folder (/sys/bus/iio/devices/iio:deviceN), its character device
//         (/dev/iio:deviceN) or an evdev node (/dev/input/eventN).
// Throws std::runtime_error naming PATH and what is wrong with it (missing, not an
// accelerometer, no scale).
std::shared_ptr<Accelerometer> open_accelerometer(const std::string& choice,
                                                  const SensorRoots& roots,
                                                  std::shared_ptr<SensorIo> io,
                                                  std::shared_ptr<Accelerometer> backend_own);

// The same on the running system.
std::shared_ptr<Accelerometer> open_accelerometer(const std::string& choice,
                                                  std::shared_ptr<Accelerometer> backend_own);

}  // namespace vibscore::sensors
