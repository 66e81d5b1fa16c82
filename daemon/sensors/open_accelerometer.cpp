#include "daemon/sensors/open_accelerometer.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "daemon/sensors/evdev_accelerometer.hpp"
#include "daemon/sensors/iio_accelerometer.hpp"

namespace vibscore::sensors {

namespace {

namespace fs = std::filesystem;

std::shared_ptr<Accelerometer> open_path(const fs::path& path, const SensorRoots& roots,
                                         const std::shared_ptr<SensorIo>& io) {
    const std::string name = path.filename().string();
    if (name.starts_with("iio:device")) {
        // The folder or the character device: both name the same device.
        const fs::path folder = roots.iio_devices / name;
        const auto listed = io->list(roots.iio_devices);
        if (std::find(listed.begin(), listed.end(), name) == listed.end()) {
            throw std::runtime_error(path.string() + ": no such IIO device (" + folder.string() +
                                     " is not there)");
        }
        return open_iio_accelerometer(folder, roots, io);
    }
    if (name.starts_with("event")) {
        if (!is_evdev_accelerometer(path, *io)) {
            throw std::runtime_error(path.string() +
                                     ": not an evdev accelerometer (missing, not readable, or "
                                     "without INPUT_PROP_ACCELEROMETER and ABS_X/Y/Z)");
        }
        return open_evdev_accelerometer(path, io);
    }
    throw std::runtime_error(path.string() +
                             ": not an accelerometer vibscored can read: name an IIO device "
                             "(/sys/bus/iio/devices/iio:deviceN or /dev/iio:deviceN) or an evdev "
                             "node (/dev/input/eventN)");
}

}  // namespace

std::shared_ptr<Accelerometer> open_accelerometer(const std::string& choice,
                                                  const SensorRoots& roots,
                                                  std::shared_ptr<SensorIo> io,
                                                  std::shared_ptr<Accelerometer> backend_own) {
    if (choice != "auto") {
        return open_path(choice, roots, io);
    }
    for (const auto& name : io->list(roots.iio_devices)) {
        if (name.starts_with("iio:device") && is_iio_accelerometer(roots.iio_devices / name, *io)) {
            return open_iio_accelerometer(roots.iio_devices / name, roots, io);
        }
    }
    for (const auto& name : io->list(roots.dev / "input")) {
        if (name.starts_with("event") && is_evdev_accelerometer(roots.dev / "input" / name, *io)) {
            return open_evdev_accelerometer(roots.dev / "input" / name, io);
        }
    }
    return backend_own;
}

std::shared_ptr<Accelerometer> open_accelerometer(const std::string& choice,
                                                  std::shared_ptr<Accelerometer> backend_own) {
    return open_accelerometer(choice, SensorRoots{}, system_sensor_io(), std::move(backend_own));
}

}  // namespace vibscore::sensors
