#include "daemon/drivers/led_vibrator_actuator.hpp"

#include <algorithm>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "daemon/drivers/drive_levels.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::drivers {

namespace {

constexpr const char* kTransient = "transient";

// The selected trigger of an LED's `trigger` attribute: "none [transient] timer" -> transient.
std::optional<std::string> selected_trigger(const std::string& list) {
    const auto open = list.find('[');
    const auto close = list.find(']', open);
    if (open == std::string::npos || close == std::string::npos) {
        return std::nullopt;
    }
    return list.substr(open + 1, close - open - 1);
}

// amplitude-path: absolute (and then under sysfs-root) or relative to the device's directory.
std::optional<AmplitudeAttribute> read_amplitude(DriverSettings& read,
                                                 const std::filesystem::path& sysfs_root,
                                                 const std::filesystem::path& device_dir) {
    const auto text = read.text("amplitude-path");
    if (!text) {
        return std::nullopt;
    }
    const std::filesystem::path given(*text);
    const auto path = (given.is_absolute() ? given : device_dir / given).lexically_normal();
    const auto inside = path.lexically_relative(sysfs_root.lexically_normal());
    if (inside.empty() || *inside.begin() == "..") {
        throw SettingError("amplitude-path",
                           read.driver() + " setting amplitude-path = " + quoted_text(*text) +
                               ": expected an attribute under " + sysfs_root.string());
    }
    return AmplitudeAttribute{path, read.integer("amplitude-max", 255, 1, 1'000'000)};
}

SysfsVibratorSettings read_common(DriverSettings& read, const char* name_key,
                                  const std::filesystem::path& class_dir) {
    SysfsVibratorSettings settings;
    settings.sysfs_root = read.text("sysfs-root", settings.sysfs_root.string());
    settings.name = read.text(name_key, settings.name);
    if (settings.name.find('/') != std::string::npos || settings.name == "." ||
        settings.name == "..") {
        throw SettingError(name_key, read.driver() + " setting " + name_key + " = " +
                                         quoted_text(settings.name) +
                                         ": expected a device name, not a path");
    }
    settings.duration_ms = read.integer("duration-ms", settings.duration_ms, 1, 600'000);
    settings.amplitude =
        read_amplitude(read, settings.sysfs_root, settings.sysfs_root / class_dir / settings.name);
    read.reject_unknown();
    return settings;
}

}  // namespace

SysfsVibrator::SysfsVibrator(SysfsVibratorSettings settings,
                             std::unique_ptr<SysfsAttributes> attributes)
    : settings_(std::move(settings)), attributes_(std::move(attributes)) {}

Capabilities SysfsVibrator::capabilities() const {
    Capabilities capabilities;
    capabilities.amplitude_control = settings_.amplitude.has_value();
    capabilities.max_on_time_s = static_cast<double>(settings_.duration_ms) / 1000.0;
    capabilities.off_timer = true;
    return capabilities;
}

void SysfsVibrator::set_off_timer(double seconds) {
    // Rounded up: the kernel must not end a note before the score does. At least 1 ms, since 0
    // means "no timer" to both interfaces.
    const auto ms = static_cast<long>(std::ceil(seconds * 1000.0 - 1e-6));
    off_timer_ms_ = std::clamp(ms, 1L, settings_.duration_ms);
}

long SysfsVibrator::take_on_time_ms() {
    const long ms = off_timer_ms_.value_or(settings_.duration_ms);
    off_timer_ms_.reset();
    return ms;
}

void SysfsVibrator::apply(const Drive& drive) {
    const double amplitude = drive_amplitude(drive);
    if (amplitude == 0.0) {
        switch_off();
        return;
    }
    if (settings_.amplitude) {
        const long value = std::lround(amplitude * static_cast<double>(settings_.amplitude->max));
        if (amplitude_written_ != value) {
            amplitude_written_.reset();
            attributes_->write(settings_.amplitude->path, std::to_string(value));
            amplitude_written_ = value;
        }
    }
    switch_on();
}

void SysfsVibrator::off() noexcept {
    try {
        switch_off();
        off_failure_logged_ = false;
    } catch (const std::exception& error) {
        // off() runs on every error path: say it once per run of failures.
        if (!off_failure_logged_) {
            off_failure_logged_ = true;
            log::warning(std::string(driver_name()) + ": cannot stop: " + error.what());
        }
    }
}

LedVibratorActuator::LedVibratorActuator(SysfsVibratorSettings settings,
                                         std::unique_ptr<SysfsAttributes> attributes)
    : SysfsVibrator(std::move(settings), std::move(attributes)),
      led_dir_(this->settings().sysfs_root / "class" / "leds" / this->settings().name) {
    if (!this->attributes().exists(led_dir_)) {
        throw DeviceError(led_dir_.string() + ": no such LED");
    }
    previous_trigger_ = selected_trigger(this->attributes().read(led_dir_ / "trigger"));
    // Changing the trigger switches the LED off; the transient trigger adds its attributes.
    this->attributes().write(led_dir_ / "trigger", kTransient);
    try {
        if (!wait_until_exists(this->attributes(), led_dir_ / "activate")) {
            throw DeviceError((led_dir_ / "activate").string() +
                              ": did not appear after selecting the transient trigger");
        }
        this->attributes().write(led_dir_ / "state", "1");
        this->attributes().write(led_dir_ / "duration",
                                 std::to_string(this->settings().duration_ms));
    } catch (...) {
        // The destructor does not run for a half-made object.
        restore_trigger();
        throw;
    }
}

LedVibratorActuator::~LedVibratorActuator() {
    off();
    restore_trigger();
}

void LedVibratorActuator::restore_trigger() noexcept {
    if (!previous_trigger_ || *previous_trigger_ == kTransient) {
        return;
    }
    try {
        attributes().write(led_dir_ / "trigger", *previous_trigger_);
    } catch (const std::exception& error) {
        log::warning(std::string("led-vibrator: cannot restore the trigger: ") + error.what());
    }
}

void LedVibratorActuator::switch_on() {
    if (has_off_timer()) {
        attributes().write(led_dir_ / "duration", std::to_string(take_on_time_ms()));
    }
    attributes().write(led_dir_ / "activate", "1");
}

void LedVibratorActuator::switch_off() {
    attributes().write(led_dir_ / "activate", "0");
}

TimedOutputActuator::TimedOutputActuator(SysfsVibratorSettings settings,
                                         std::unique_ptr<SysfsAttributes> attributes)
    : SysfsVibrator(std::move(settings), std::move(attributes)),
      enable_(this->settings().sysfs_root / "class" / "timed_output" / this->settings().name /
              "enable") {
    if (!this->attributes().exists(enable_)) {
        throw DeviceError(enable_.string() + ": no such timed_output device");
    }
    switch_off();
}

TimedOutputActuator::~TimedOutputActuator() {
    off();
}

void TimedOutputActuator::switch_on() {
    attributes().write(enable_, std::to_string(take_on_time_ms()));
}

void TimedOutputActuator::switch_off() {
    attributes().write(enable_, "0");
}

std::unique_ptr<Actuator> make_led_vibrator_actuator(
    const std::map<std::string, std::string>& settings,
    std::unique_ptr<SysfsAttributes> attributes) {
    DriverSettings read("led-vibrator", settings);
    return std::make_unique<LedVibratorActuator>(read_common(read, "led", "class/leds"),
                                                 std::move(attributes));
}

std::unique_ptr<Actuator> make_timed_output_actuator(
    const std::map<std::string, std::string>& settings,
    std::unique_ptr<SysfsAttributes> attributes) {
    DriverSettings read("timed-output", settings);
    return std::make_unique<TimedOutputActuator>(read_common(read, "name", "class/timed_output"),
                                                 std::move(attributes));
}

}  // namespace vibscore::drivers
