#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/evdev_discovery.hpp"

// `driver = auto` (the Debian package's default): a phone vibrates after install with nothing
// configured, and a machine with no actuator still serves, on the simulation, saying why.
namespace vibscore::drivers {

inline constexpr const char* kAutoDriver = "auto";

// The backends auto tries after evdev, in this order, each only where the configuration has its
// section: their devices (a GPIO line, a PWM channel, an LED's name) cannot be guessed safely.
inline constexpr const char* kAutoConfiguredDrivers[] = {"gpio-erm", "gpio-lra", "sysfs-pwm",
                                                         "led-vibrator", "timed-output"};

struct AutoChoice {
    std::string driver;  // the backend that opened
    // Why, for people (the DriverReason property, the log): the device found, or what was
    // searched and how to configure a backend.
    std::string reason;
    bool fell_back = false;  // nothing found: driver is sim
    std::unique_ptr<Actuator> actuator;
};

// What the choice asks of the world; the daemon's answers come from the kernel and the
// configuration (auto_search), a unit test's from fakes.
struct AutoSearch {
    // Where driver = auto is set ("file:line"), if the configuration says.
    std::string where;
    // The configuration's sections by name, each with where it begins ("file:line", or "" when
    // the settings came from no file).
    std::map<std::string, std::string> sections;
    // The event node the [evdev] section names (device =), if any.
    std::optional<std::string> evdev_device;
    // evdev's discovery, as the evdev backend runs it without device =: the node it takes, or
    // DeviceError saying where it looked and what it found.
    std::function<DiscoveredDevice()> discover;
    // Opens a built-in backend with its configured settings, as make_actuator: DeviceError (or
    // another runtime error) when its device is not there, std::invalid_argument for a bad
    // setting.
    std::function<std::unique_ptr<Actuator>(const std::string& driver)> open;
};

// The first backend that finds a device: evdev (the device [evdev] names, else discovery: the
// force-feedback node udev tags FEEDBACKD_TYPE=vibra, else the first with force feedback), then
// each configured section of kAutoConfiguredDrivers; else sim, with fell_back set. A backend
// whose device is missing or will not open is passed over (the reason says why); a bad setting
// is not: std::invalid_argument leaves, as for a driver named outright.
AutoChoice choose_driver(const AutoSearch& search);

// The search on this machine: the sections and where driver = auto is set, evdev discovery on
// the kernel with the [evdev] section's input-dir and udev-data, and `open`.
AutoSearch auto_search(std::string where, std::map<std::string, std::string> sections,
                       const std::map<std::string, std::string>& evdev_settings,
                       std::function<std::unique_ptr<Actuator>(const std::string&)> open);

}  // namespace vibscore::drivers
