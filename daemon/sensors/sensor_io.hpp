#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

// What the accelerometer readers need of the kernel, and no more: sysfs attributes, a character
// device to stream from (an IIO buffer, an evdev node) and the monotonic clock. The system's
// implementation is a few lines of POSIX; tests give a fake (tests/fakes/fake_sensor_io.hpp).
namespace vibscore::sensors {

// An evdev absolute axis as EVIOCGABS reports it.
struct AbsAxis {
    std::int32_t minimum = 0, maximum = 0;
    std::int32_t resolution = 0;  // units per g for an accelerometer (0: not given)
};

// One open character device.
class SensorDevice {
  public:
    virtual ~SensorDevice() = default;
    // What arrives within `timeout` (empty: nothing did). Throws std::runtime_error naming the
    // device when it fails or goes away.
    virtual std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) = 0;
    // evdev: INPUT_PROP_* of the device (EVIOCGPROP) and an axis (EVIOCGABS; nullopt when the
    // device has none); its event times on CLOCK_MONOTONIC (EVIOCSCLOCKID).
    virtual bool has_input_property(unsigned property) = 0;
    virtual std::optional<AbsAxis> abs_axis(unsigned code) = 0;
    virtual void use_monotonic_clock() = 0;
};

class SensorIo {
  public:
    virtual ~SensorIo() = default;
    // An attribute's content without its trailing newline; nullopt when there is no such file.
    // Throws std::runtime_error naming it when it exists but cannot be read.
    virtual std::optional<std::string> read_file(const std::filesystem::path& file) = 0;
    // Throws std::runtime_error naming the file, the value and the kernel's reason.
    virtual void write_file(const std::filesystem::path& file, const std::string& value) = 0;
    // The names in a folder, sorted; empty when there is no such folder.
    virtual std::vector<std::string> list(const std::filesystem::path& folder) = 0;
    // Opens a device for reading. Throws std::runtime_error naming it and the reason.
    virtual std::unique_ptr<SensorDevice> open_device(const std::filesystem::path& device) = 0;
    virtual std::int64_t now_ns() = 0;  // CLOCK_MONOTONIC
};

// The running system's.
std::shared_ptr<SensorIo> system_sensor_io();

// Where the kernel shows its devices: the system's folders, or a test's tree.
struct SensorRoots {
    std::filesystem::path iio_devices = "/sys/bus/iio/devices";
    std::filesystem::path dev = "/dev";
    std::filesystem::path input_class = "/sys/class/input";
};

}  // namespace vibscore::sensors
