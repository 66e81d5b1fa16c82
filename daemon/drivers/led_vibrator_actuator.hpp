#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/sysfs_attributes.hpp"

namespace vibscore::drivers {

// An optional strength attribute of an on/off vibrator: round(amplitude × max) is written to it.
struct AmplitudeAttribute {
    std::filesystem::path path;
    long max = 255;
};

struct SysfsVibratorSettings {
    std::filesystem::path sysfs_root = "/sys";
    std::string name = "vibrator";  // the LED, or the timed_output device
    long duration_ms = 5000;        // how long one switch-on lasts at most
    std::optional<AmplitudeAttribute> amplitude;
};

// A vibrator that the kernel switches off by itself after a time it is given: the failsafe when
// the daemon dies while it vibrates. The player gives the time until the score switches off
// (set_off_timer, at most duration_ms), so a note ends on time even then; without one, a
// switch-on lasts duration_ms. Both kinds report that limit as max_on_time_s, and amplitude
// control only with an amplitude attribute (otherwise the player pulse-modulates strength).
class SysfsVibrator : public Actuator {
  public:
    Capabilities capabilities() const override;
    void set_off_timer(double seconds) override;

    // amplitude > 0 switches on (after writing the strength, if there is an amplitude
    // attribute); 0 switches off. Throws DeviceError naming the attribute.
    void apply(const Drive& drive) override;
    void off() noexcept override;

  protected:
    SysfsVibrator(SysfsVibratorSettings settings, std::unique_ptr<SysfsAttributes> attributes);

    virtual void switch_on() = 0;
    virtual void switch_off() = 0;

    const SysfsVibratorSettings& settings() const { return settings_; }
    SysfsAttributes& attributes() { return *attributes_; }
    // For the switch-on under way: the kernel timer's time in ms (set_off_timer's, once).
    long take_on_time_ms();
    // Whether set_off_timer gave a time for the next switch-on.
    bool has_off_timer() const { return off_timer_ms_.has_value(); }

  private:
    std::optional<long> off_timer_ms_;
    SysfsVibratorSettings settings_;
    std::unique_ptr<SysfsAttributes> attributes_;
    std::optional<long> amplitude_written_;
    bool off_failure_logged_ = false;
};

// "led-vibrator": <sysfs-root>/class/leds/<name> with the transient trigger. Open: trigger =
// transient, state = 1, duration = duration_ms. On: duration = the off timer's time when the
// player gave one, then activate = 1 (the kernel starts the duration timer; while it runs,
// further writes change nothing). Off: activate = 0. Close: off and
// the LED's previous trigger back.
class LedVibratorActuator : public SysfsVibrator {
  public:
    // Throws DeviceError naming the path when the LED is missing or refuses the trigger.
    LedVibratorActuator(SysfsVibratorSettings settings,
                        std::unique_ptr<SysfsAttributes> attributes);
    ~LedVibratorActuator() override;
    std::string_view driver_name() const override { return "led-vibrator"; }

  private:
    void switch_on() override;
    void switch_off() override;
    void restore_trigger() noexcept;

    std::filesystem::path led_dir_;
    std::optional<std::string> previous_trigger_;
};

// "timed-output": <sysfs-root>/class/timed_output/<name>/enable (the Android interface). On:
// enable = the off timer's time, or duration_ms (each write restarts the kernel's timer). Off:
// enable = 0.
class TimedOutputActuator : public SysfsVibrator {
  public:
    // Throws DeviceError naming the path when the device is missing or refuses the first off.
    TimedOutputActuator(SysfsVibratorSettings settings,
                        std::unique_ptr<SysfsAttributes> attributes);
    ~TimedOutputActuator() override;
    std::string_view driver_name() const override { return "timed-output"; }

  private:
    void switch_on() override;
    void switch_off() override;

    std::filesystem::path enable_;
};

// "led-vibrator" settings: sysfs-root (default /sys), led (default vibrator), duration-ms
// (1..600000, default 5000), amplitude-path (absolute under sysfs-root, or relative to the LED's
// directory), amplitude-max (with amplitude-path; 1..1000000, default 255).
std::unique_ptr<Actuator> make_led_vibrator_actuator(
    const std::map<std::string, std::string>& settings,
    std::unique_ptr<SysfsAttributes> attributes = make_kernel_sysfs_attributes());

// "timed-output" settings: as for led-vibrator with name (default vibrator) instead of led;
// a relative amplitude-path is relative to the timed_output device's directory.
std::unique_ptr<Actuator> make_timed_output_actuator(
    const std::map<std::string, std::string>& settings,
    std::unique_ptr<SysfsAttributes> attributes = make_kernel_sysfs_attributes());

}  // namespace vibscore::drivers
