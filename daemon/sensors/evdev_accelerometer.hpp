#pragma once

#include <filesystem>
#include <memory>

#include "daemon/sensors/accelerometer.hpp"
#include "daemon/sensors/sensor_io.hpp"

namespace vibscore::sensors {

// Whether an evdev node (/dev/input/eventN) is an accelerometer: INPUT_PROP_ACCELEROMETER with
// ABS_X, ABS_Y and ABS_Z.
bool is_evdev_accelerometer(const std::filesystem::path& node, SensorIo& io);

// The reader for an evdev accelerometer: ABS_X/Y/Z events, each reading complete at SYN_REPORT,
// timed by the events' own times on CLOCK_MONOTONIC; values in units per g (the axes'
// resolution) put in m/s². Throws std::runtime_error naming the node when it is not one, or an
// axis has no resolution (then its units are unknown).
std::unique_ptr<Accelerometer> open_evdev_accelerometer(const std::filesystem::path& node,
                                                        std::shared_ptr<SensorIo> io);

}  // namespace vibscore::sensors
