#include "daemon/drivers/sysfs_pwm_actuator.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "daemon/drivers/drive_levels.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::drivers {

namespace {

std::int64_t period_ns(double frequency_hz) {
    return std::llround(1e9 / frequency_hz);
}

}  // namespace

SysfsPwmActuator::SysfsPwmActuator(const SysfsPwmSettings& settings,
                                   std::unique_ptr<SysfsAttributes> attributes,
                                   std::unique_ptr<GpioLines> direction)
    : settings_(settings),
      attributes_(std::move(attributes)),
      chip_dir_(settings.sysfs_root / "class" / "pwm" /
                ("pwmchip" + std::to_string(settings.chip))),
      channel_dir_(chip_dir_ / ("pwm" + std::to_string(settings.channel))),
      direction_(std::move(direction)) {
    try {
        open_channel();
    } catch (...) {
        // The destructor does not run for a half-made object: undo the export here.
        close_channel();
        throw;
    }
}

SysfsPwmActuator::~SysfsPwmActuator() {
    close_channel();
}

void SysfsPwmActuator::open_channel() {
    if (!attributes_->exists(chip_dir_)) {
        throw DeviceError(chip_dir_.string() + ": no such PWM chip");
    }
    if (!attributes_->exists(channel_dir_)) {
        attributes_->write(chip_dir_ / "export", std::to_string(settings_.channel));
        exported_ = true;
        if (!wait_until_exists(*attributes_, attribute("enable"))) {
            throw DeviceError(channel_dir_.string() + ": did not appear after export");
        }
    }
    const double frequency_hz =
        settings_.mode == SysfsPwmMode::erm ? settings_.carrier_hz : settings_.resonance_hz;
    // A channel left running (by a crash, or by someone else) stops here before it is enabled.
    set(period_ns(frequency_hz), 0);
    attributes_->write(attribute("enable"), "1");
}

void SysfsPwmActuator::close_channel() noexcept {
    const auto attempt = [this](const char* what, auto&& step) {
        try {
            step();
        } catch (const std::exception& error) {
            log::warning(std::string("sysfs-pwm: ") + what + ": " + error.what());
        }
    };
    if (attributes_->exists(channel_dir_)) {
        attempt("stopping", [this] { write("duty_cycle", 0); });
        attempt("disabling", [this] { attributes_->write(attribute("enable"), "0"); });
    }
    if (exported_) {
        attempt("unexporting", [this] {
            attributes_->write(chip_dir_ / "unexport", std::to_string(settings_.channel));
        });
    }
}

Capabilities SysfsPwmActuator::capabilities() const {
    Capabilities capabilities;
    capabilities.amplitude_control = true;
    capabilities.frequency_control = settings_.mode == SysfsPwmMode::lra;
    capabilities.reverse = direction_ != nullptr;
    return capabilities;
}

std::int64_t SysfsPwmActuator::read_number(const char* name) {
    const std::string text = attributes_->read(attribute(name));
    std::int64_t value = 0;
    const char* const end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc{} || ptr != end || value < 0) {
        throw DeviceError(attribute(name).string() + ": expected a number of nanoseconds, read \"" +
                          text + "\"");
    }
    return value;
}

void SysfsPwmActuator::write(const char* name, std::int64_t value) {
    attributes_->write(attribute(name), std::to_string(value));
}

void SysfsPwmActuator::set(std::int64_t period, std::int64_t duty) {
    try {
        if (!period_ns_ || !duty_ns_) {
            period_ns_ = read_number("period");
            duty_ns_ = read_number("duty_cycle");
        }
        if (period != *period_ns_) {
            // The kernel refuses duty_cycle > period at every step: when the period shrinks
            // below the present duty_cycle, the duty_cycle goes first.
            if (*duty_ns_ > period) {
                write("duty_cycle", duty);
                duty_ns_ = duty;
            }
            write("period", period);
            period_ns_ = period;
        }
        if (duty != *duty_ns_) {
            write("duty_cycle", duty);
            duty_ns_ = duty;
        }
    } catch (...) {
        period_ns_.reset();
        duty_ns_.reset();
        throw;
    }
}

void SysfsPwmActuator::turn(bool backwards) {
    if (backwards == backwards_) {
        return;
    }
    if (duty_ns_ != 0) {
        write("duty_cycle", 0);
        duty_ns_ = 0;
    }
    direction_->set_values({backwards ? 1 : 0});
    backwards_ = backwards;
}

void SysfsPwmActuator::apply(const Drive& drive) {
    double amplitude = drive_amplitude(drive);
    if (direction_ && drive.amplitude < 0.0) {
        amplitude = std::min(-drive.amplitude, 1.0);
        turn(true);
    } else if (direction_ && amplitude > 0.0) {
        turn(false);
    }
    if (settings_.mode == SysfsPwmMode::erm) {
        const std::int64_t period = period_ns(settings_.carrier_hz);
        set(period, std::llround(amplitude * static_cast<double>(period)));
        return;
    }
    if (amplitude == 0.0 && period_ns_) {
        // Silence needs no new period; leaving it avoids a write per rest.
        set(*period_ns_, 0);
        return;
    }
    const std::int64_t period = period_ns(lra_frequency_hz(drive, settings_.resonance_hz));
    set(period, std::llround(lra_pulse_share(amplitude) * static_cast<double>(period) / 2.0));
}

void SysfsPwmActuator::off() noexcept {
    try {
        if (duty_ns_ != 0) {
            write("duty_cycle", 0);
            duty_ns_ = 0;
        }
        if (direction_ && backwards_) {
            direction_->set_values({0});
            backwards_ = false;
        }
        off_failure_logged_ = false;
    } catch (const std::exception& error) {
        duty_ns_.reset();
        // off() runs on every error path: say it once per run of failures.
        if (!off_failure_logged_) {
            off_failure_logged_ = true;
            log::warning(std::string("sysfs-pwm: cannot stop: ") + error.what());
        }
    }
}

std::unique_ptr<Actuator> make_sysfs_pwm_actuator(
    const std::map<std::string, std::string>& settings, std::unique_ptr<SysfsAttributes> attributes,
    const GpioLinesOpener& open_direction) {
    DriverSettings read("sysfs-pwm", settings);
    SysfsPwmSettings pwm;
    pwm.sysfs_root = read.text("sysfs-root", pwm.sysfs_root.string());
    pwm.chip = read.integer("chip", pwm.chip, 0, 9999);
    pwm.channel = read.integer("channel", pwm.channel, 0, 9999);
    pwm.mode =
        read.choice("mode", "erm", {"erm", "lra"}) == "erm" ? SysfsPwmMode::erm : SysfsPwmMode::lra;
    // Each mode has its own frequency key; the other one is reported as unknown.
    if (pwm.mode == SysfsPwmMode::erm) {
        pwm.carrier_hz = read.number("carrier-hz", pwm.carrier_hz, 10.0, 1'000'000.0);
    } else {
        pwm.resonance_hz = read.number("resonance-hz", pwm.resonance_hz, kMinLraHz, kMaxLraHz);
    }
    const std::string direction_chip = read.text("direction-chip", "gpiochip0");
    const auto direction_line = read.integer("direction-line", 0, 65535);
    if (read.has("direction-chip") && !direction_line) {
        throw SettingError("direction-chip",
                           "sysfs-pwm setting direction-chip = " + quoted_text(direction_chip) +
                               " needs direction-line: the line offset on that chip");
    }
    read.reject_unknown();
    std::unique_ptr<GpioLines> direction;
    if (direction_line) {
        direction = open_direction(direction_chip, {static_cast<unsigned>(*direction_line)});
    }
    return std::make_unique<SysfsPwmActuator>(pwm, std::move(attributes), std::move(direction));
}

}  // namespace vibscore::drivers
