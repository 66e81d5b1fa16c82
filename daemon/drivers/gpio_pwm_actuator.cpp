#include "daemon/drivers/gpio_pwm_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "daemon/drivers/drive_levels.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::drivers {

namespace {

constexpr long kMaxLineOffset = 65535;

std::int64_t period_ns(double frequency_hz) {
    return std::llround(1e9 / frequency_hz);
}

std::vector<int> with_enable(std::vector<int> values, bool enable_line) {
    if (enable_line) {
        values.push_back(1);
    }
    return values;
}

// The drive's amplitude within -1..1; NaN counts as 0 (off).
double signed_amplitude(const Drive& drive) {
    return std::isnan(drive.amplitude) ? 0.0 : std::clamp(drive.amplitude, -1.0, 1.0);
}

// The line offsets `keys` name, all read before any is found missing, so that a misspelt key
// ("lines = 17") is reported as unknown rather than the key it misspells as missing.
std::vector<unsigned> required_lines(DriverSettings& read, std::vector<std::string> keys) {
    std::vector<std::optional<long>> offsets;
    for (const auto& key : keys) {
        offsets.push_back(read.integer(key, 0, kMaxLineOffset));
    }
    std::vector<unsigned> lines;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (!offsets[i]) {
            throw read.missing(keys[i], "the line offset on the chip");
        }
        lines.push_back(static_cast<unsigned>(*offsets[i]));
    }
    return lines;
}

// The direction line (gpio-erm), then the enable line, if configured, go last; no line may be
// named twice.
std::vector<unsigned> with_enable_line(DriverSettings& read, std::vector<unsigned> offsets,
                                       GpioPwmSettings& settings) {
    std::vector<std::string> keys = settings.kind == GpioPwmKind::erm
                                        ? std::vector<std::string>{"line"}
                                        : std::vector<std::string>{"line-a", "line-b"};
    if (settings.kind == GpioPwmKind::erm) {
        if (const auto direction = read.integer("direction-line", 0, kMaxLineOffset)) {
            offsets.push_back(static_cast<unsigned>(*direction));
            keys.emplace_back("direction-line");
            settings.direction_line = true;
        }
    }
    if (const auto enable = read.integer("enable-line", 0, kMaxLineOffset)) {
        offsets.push_back(static_cast<unsigned>(*enable));
        keys.emplace_back("enable-line");
        settings.enable_line = true;
    }
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        for (std::size_t j = i + 1; j < offsets.size(); ++j) {
            if (offsets[i] == offsets[j]) {
                throw SettingError(keys[j], read.driver() + " settings name line " +
                                                std::to_string(offsets[i]) +
                                                " twice: every line needs its own offset");
            }
        }
    }
    return offsets;
}

std::unique_ptr<Actuator> finish_gpio_actuator(DriverSettings& read, GpioPwmSettings settings,
                                               const std::vector<unsigned>& offsets,
                                               const std::string& chip,
                                               const GpioLinesOpener& open) {
    settings.rt_priority = static_cast<int>(read.integer("rt-priority", 50, 0, 99));
    read.reject_unknown();
    return std::make_unique<GpioPwmActuator>(settings, open(chip, offsets));
}

}  // namespace

PwmWaveform erm_waveform(double amplitude, double carrier_hz, bool enable_line,
                         bool direction_line) {
    const bool backwards = amplitude < 0.0;
    if (backwards && !direction_line) {
        return {};  // no way to drive it backwards
    }
    const std::int64_t period = period_ns(carrier_hz);
    const std::int64_t high = std::llround(std::abs(amplitude) * static_cast<double>(period));
    if (!(high > 0)) {
        return {};
    }
    const auto lines = [&](int motor) {
        std::vector<int> values{motor};
        if (direction_line) {
            values.push_back(backwards ? 1 : 0);
        }
        return with_enable(values, enable_line);
    };
    if (high >= period) {
        return {period, {{0, lines(1)}}};
    }
    return {period, {{0, lines(1)}, {high, lines(0)}}};
}

PwmWaveform lra_waveform(double amplitude, double frequency_hz, bool enable_line) {
    const std::int64_t period = period_ns(frequency_hz);
    const std::int64_t half = period / 2;
    const std::int64_t high = std::llround(lra_pulse_share(amplitude) * static_cast<double>(half));
    if (!(high > 0)) {
        return {};
    }
    // Anti-phase is the same drive half a period on: B leads.
    const bool anti = amplitude < 0.0;
    const std::vector<int> a_high = with_enable({anti ? 0 : 1, anti ? 1 : 0}, enable_line);
    const std::vector<int> b_high = with_enable({anti ? 1 : 0, anti ? 0 : 1}, enable_line);
    if (high >= half) {
        return {period, {{0, a_high}, {half, b_high}}};
    }
    const std::vector<int> both_low = with_enable({0, 0}, enable_line);
    return {period, {{0, a_high}, {high, both_low}, {half, b_high}, {half + high, both_low}}};
}

GpioPwmActuator::GpioPwmActuator(const GpioPwmSettings& settings, std::unique_ptr<GpioLines> lines)
    : settings_(settings),
      lines_description_(lines->describe()),
      thread_(std::move(lines), settings.rt_priority) {}

std::string_view GpioPwmActuator::driver_name() const {
    return settings_.kind == GpioPwmKind::erm ? "gpio-erm" : "gpio-lra";
}

Capabilities GpioPwmActuator::capabilities() const {
    Capabilities capabilities;
    capabilities.amplitude_control = true;
    capabilities.frequency_control = settings_.kind == GpioPwmKind::lra;
    capabilities.reverse = settings_.kind == GpioPwmKind::lra || settings_.direction_line;
    return capabilities;
}

void GpioPwmActuator::hand_over(PwmWaveform waveform) {
    // The player repeats drives along ramps; an unchanged waveform need not wake the thread.
    if (handed_over_ == waveform) {
        return;
    }
    handed_over_ = waveform;
    thread_.play(std::move(waveform));
}

void GpioPwmActuator::apply(const Drive& drive) {
    if (auto error = thread_.take_error()) {
        // The thread has gone quiet with the lines low; the next drive starts afresh.
        handed_over_.reset();
        throw DeviceError(std::string(driver_name()) + " on " + lines_description_ + ": " + *error);
    }
    const double amplitude = signed_amplitude(drive);
    hand_over(settings_.kind == GpioPwmKind::erm
                  ? erm_waveform(amplitude, settings_.frequency_hz, settings_.enable_line,
                                 settings_.direction_line)
                  : lra_waveform(amplitude, lra_frequency_hz(drive, settings_.frequency_hz),
                                 settings_.enable_line));
}

void GpioPwmActuator::off() noexcept {
    try {
        hand_over({});
    } catch (...) {
        // Only allocation can fail here; the thread then keeps its last waveform until the
        // next call, which is all that can be done.
    }
}

std::unique_ptr<Actuator> make_gpio_erm_actuator(const std::map<std::string, std::string>& settings,
                                                 const GpioLinesOpener& open) {
    DriverSettings read("gpio-erm", settings);
    GpioPwmSettings erm;
    erm.kind = GpioPwmKind::erm;
    const std::string chip = read.text("chip", "gpiochip0");
    const auto offsets = with_enable_line(read, required_lines(read, {"line"}), erm);
    erm.frequency_hz = read.number("carrier-hz", 1000.0, 10.0, 20000.0);
    return finish_gpio_actuator(read, erm, offsets, chip, open);
}

std::unique_ptr<Actuator> make_gpio_lra_actuator(const std::map<std::string, std::string>& settings,
                                                 const GpioLinesOpener& open) {
    DriverSettings read("gpio-lra", settings);
    GpioPwmSettings lra;
    lra.kind = GpioPwmKind::lra;
    const std::string chip = read.text("chip", "gpiochip0");
    const auto offsets = with_enable_line(read, required_lines(read, {"line-a", "line-b"}), lra);
    lra.frequency_hz = read.number("resonance-hz", 175.0, kMinLraHz, kMaxLraHz);
    return finish_gpio_actuator(read, lra, offsets, chip, open);
}

}  // namespace vibscore::drivers
