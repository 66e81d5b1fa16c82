#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_pwm_actuator.hpp"
#include "daemon/drivers/sysfs_attributes.hpp"

namespace vibscore::drivers {

enum class SysfsPwmMode { erm, lra };

struct SysfsPwmSettings {
    std::filesystem::path sysfs_root = "/sys";
    long chip = 0;     // pwmchipN
    long channel = 0;  // pwmK of that chip
    SysfsPwmMode mode = SysfsPwmMode::erm;
    double carrier_hz = 20000.0;  // erm: inaudible, and free in hardware
    double resonance_hz = 175.0;  // lra: the period when a drive leaves the frequency open
};

// A hardware PWM channel through <sysfs-root>/class/pwm/pwmchipN/pwmK ("sysfs-pwm").
//   erm: period = 1/carrier, duty_cycle = amplitude × period.
//   lra: period = 1/(the drive's frequency), duty_cycle = lra_pulse_share(amplitude) × period / 2
//        (the pulses' fundamental, which the LRA answers, is then proportional to the amplitude).
// The channel stays enabled from open to close; off is duty_cycle 0, the one output level the
// PWM API defines (a disabled channel's pin level is up to the controller).
// With a direction line (a GPIO on an H-bridge's phase pin) the drive can be reversed: a negative
// amplitude raises it (after setting duty_cycle 0, so the bridge never switches under load) and
// drives |amplitude|; the reverse-drive capability the renderer brakes with.
class SysfsPwmActuator : public Actuator {
  public:
    // Exports the channel unless it is already there, then sets the period, duty_cycle 0 and
    // enable 1. Throws DeviceError naming the path (no such chip, export refused, a write
    // refused); a channel it exported is unexported again first. `direction`, when given, is one
    // low output line.
    SysfsPwmActuator(const SysfsPwmSettings& settings, std::unique_ptr<SysfsAttributes> attributes,
                     std::unique_ptr<GpioLines> direction = nullptr);
    // duty_cycle 0, enable 0, and unexport if the constructor exported the channel.
    ~SysfsPwmActuator() override;
    SysfsPwmActuator(const SysfsPwmActuator&) = delete;
    SysfsPwmActuator& operator=(const SysfsPwmActuator&) = delete;

    std::string_view driver_name() const override { return "sysfs-pwm"; }
    Capabilities capabilities() const override;

    // Throws DeviceError naming the attribute when the kernel refuses a write.
    void apply(const Drive& drive) override;
    void off() noexcept override;

  private:
    void open_channel();
    void close_channel() noexcept;
    // Writes period and duty_cycle in the order the kernel accepts (duty_cycle never above the
    // period), skipping what the channel already holds.
    void set(std::int64_t period_ns, std::int64_t duty_ns);
    std::int64_t read_number(const char* name);
    void write(const char* name, std::int64_t value);
    // Sets the direction line, with the duty cycle at 0 while it changes.
    void turn(bool backwards);
    std::filesystem::path attribute(const char* name) const { return channel_dir_ / name; }

    SysfsPwmSettings settings_;
    std::unique_ptr<SysfsAttributes> attributes_;
    std::filesystem::path chip_dir_;
    std::filesystem::path channel_dir_;
    bool exported_ = false;
    std::unique_ptr<GpioLines> direction_;
    bool backwards_ = false;  // the direction line is high
    // What the channel holds; unknown (re-read before the next change) after a failed write.
    std::optional<std::int64_t> period_ns_;
    std::optional<std::int64_t> duty_ns_;
    bool off_failure_logged_ = false;
};

// "sysfs-pwm" settings: sysfs-root (default /sys), chip (default 0), channel (default 0),
// mode erm | lra (default erm), carrier-hz (erm; 10..1000000, default 20000), resonance-hz (lra;
// 10..1000, default 175), direction-line and direction-chip (an H-bridge's direction on a GPIO
// line of that chip, default gpiochip0). Throws std::invalid_argument for a bad or unknown setting
// and DeviceError when the channel or the line cannot be set up.
std::unique_ptr<Actuator> make_sysfs_pwm_actuator(
    const std::map<std::string, std::string>& settings,
    std::unique_ptr<SysfsAttributes> attributes = make_kernel_sysfs_attributes(),
    const GpioLinesOpener& open_direction = open_gpio_lines);

}  // namespace vibscore::drivers
