#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_lines.hpp"
#include "daemon/drivers/pwm_thread.hpp"

namespace vibscore::drivers {

enum class GpioPwmKind { erm, lra };

// ERM on one line (then the direction line, then the enable line, when present): high for duty × T
// from the start of each carrier period T, duty = |amplitude|. Duty 0 is off (every line low),
// duty 1 is steadily high. A negative amplitude drives backwards: with a direction line (an
// H-bridge's phase pin) that line is high throughout; without one it is off.
PwmWaveform erm_waveform(double amplitude, double carrier_hz, bool enable_line,
                         bool direction_line = false);

// LRA on an H-bridge, lines A and B (then the enable line) in antiphase at frequency f, T = 1/f:
// A high for duty × T/2 from the period start, B high for duty × T/2 from the half period, never
// both at once, duty = lra_pulse_share(amplitude) (the pulses' fundamental, which the LRA answers,
// is then |amplitude| of the full square wave's). Duty 0 is off (every line low). A negative
// amplitude is the drive in anti-phase: B first, then A.
PwmWaveform lra_waveform(double amplitude, double frequency_hz, bool enable_line);

struct GpioPwmSettings {
    GpioPwmKind kind = GpioPwmKind::erm;
    double frequency_hz = 1000.0;  // the ERM's carrier, or the LRA's resonance
    bool enable_line = false;      // the last of the lines enables the driver IC
    int rt_priority = 50;
    bool direction_line = false;  // erm: the line after the motor line sets an H-bridge's direction
};

// Software PWM on GPIO lines ("gpio-erm", "gpio-lra"): the PwmThread makes the edges, apply()
// and off() only hand it the next waveform. The enable line is high while driving and low when
// off. gpio-lra can always drive in anti-phase (its H-bridge), gpio-erm backwards when it has a
// direction line: the reverse-drive capability the renderer brakes with.
class GpioPwmActuator : public Actuator {
  public:
    // `lines` are low and in waveform order: the motor line (erm) or A and B (lra), then the
    // enable line if there is one.
    GpioPwmActuator(const GpioPwmSettings& settings, std::unique_ptr<GpioLines> lines);

    std::string_view driver_name() const override;
    Capabilities capabilities() const override;

    // Throws DeviceError naming the chip and lines when the PWM thread met a line error since
    // the last call; the drive is then not taken.
    void apply(const Drive& drive) override;
    void off() noexcept override;

    bool realtime() const { return thread_.realtime(); }

  private:
    void hand_over(PwmWaveform waveform);

    GpioPwmSettings settings_;
    std::string lines_description_;
    PwmThread thread_;
    std::optional<PwmWaveform> handed_over_;
};

// Opens the lines of a GPIO backend; the default is the kernel's (open_gpio_lines).
using GpioLinesOpener = std::function<std::unique_ptr<GpioLines>(
    const std::string& chip, const std::vector<unsigned>& offsets)>;

// "gpio-erm" settings: chip (default gpiochip0; a name, /dev path, label or number), line
// (required), direction-line (an H-bridge's direction: with it the ERM can be driven backwards,
// so braked), enable-line, carrier-hz (10..20000, default 1000), rt-priority (0..99, default 50;
// 0 = normal scheduling). Throws std::invalid_argument for a bad, missing or unknown setting and
// DeviceError when the lines cannot be had.
std::unique_ptr<Actuator> make_gpio_erm_actuator(const std::map<std::string, std::string>& settings,
                                                 const GpioLinesOpener& open = open_gpio_lines);

// "gpio-lra" settings: chip, line-a, line-b (both required), enable-line, resonance-hz (10..1000,
// default 175), rt-priority. Errors as for gpio-erm.
std::unique_ptr<Actuator> make_gpio_lra_actuator(const std::map<std::string, std::string>& settings,
                                                 const GpioLinesOpener& open = open_gpio_lines);

}  // namespace vibscore::drivers
