#include "daemon/drivers/sim_actuator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::drivers {

namespace {

using actuator::Kind;

std::string meter_label(Kind kind) {
    return kind == Kind::erm ? "sim erm" : "sim lra";
}

// The [sim] keys that describe the simulated actuator itself.
constexpr const char* kModelKeys[] = {"model", "resonance-hz", "q", "spin-up-ms", "spin-down-ms"};

// The undeclared sim's model, as [actuator] would declare it: `model` for its kind, then the
// declaration's keys of that kind with the declaration's defaults and limits. A key of the other
// kind is refused, as in [actuator]: it would describe no actuator the sim simulates.
void read_model(DriverSettings& read, const std::map<std::string, std::string>& settings,
                actuator::Declaration& model) {
    model.kind = read.choice("model", "lra", {"erm", "lra"}) == "erm" ? Kind::erm : Kind::lra;
    const auto read_ms = [&](const actuator::Limit& limit, double& seconds) {
        seconds = read.number(limit.key, seconds * 1000.0, limit.min, limit.max) / 1000.0;
    };
    const auto read_number = [&](const actuator::Limit& limit, double& value) {
        value = read.number(limit.key, value, limit.min, limit.max);
    };
    const bool erm = model.kind == Kind::erm;
    const std::vector<const char*> other_kind =
        erm ? std::vector{actuator::kResonanceHz.key, actuator::kQ.key}
            : std::vector{actuator::kSpinUpMs.key, actuator::kSpinDownMs.key};
    for (const char* key : other_kind) {
        if (const auto found = settings.find(key); found != settings.end()) {
            throw SettingError(key, std::string("sim setting ") + key + " = " +
                                        quoted_text(found->second) +
                                        " is for model = " + (erm ? "lra" : "erm") +
                                        "; this sim is model = " + (erm ? "erm" : "lra"));
        }
    }
    if (erm) {
        read_ms(actuator::kSpinUpMs, model.spin_up_s);
        read_ms(actuator::kSpinDownMs, model.spin_down_s);
    } else {
        read_number(actuator::kResonanceHz, model.resonance_hz);
        read_number(actuator::kQ, model.q);
    }
}

// [sim] true-*: the actuator as it truly is, apart from what is declared; and its accelerometer.
void read_truth(DriverSettings& read, SimSettings& sim) {
    auto truth = sim.actuator;
    bool differs = false;
    const auto read_true = [&](const char* key, double& value, double scale, double min,
                               double max) {
        if (read.has(key)) {
            value = read.number(key, value * scale, min, max) / scale;
            differs = true;
        }
    };
    read_true("true-resonance-hz", truth.resonance_hz, 1.0, actuator::kResonanceHz.min,
              actuator::kResonanceHz.max);
    read_true("true-q", truth.q, 1.0, actuator::kQ.min, actuator::kQ.max);
    read_true("true-spin-up-ms", truth.spin_up_s, 1000.0, actuator::kSpinUpMs.min,
              actuator::kSpinUpMs.max);
    read_true("true-spin-down-ms", truth.spin_down_s, 1000.0, actuator::kSpinDownMs.min,
              actuator::kSpinDownMs.max);
    if (differs) {
        sim.truth = truth;
    }
    sim.accelerometer.rate_hz =
        read.number("accelerometer-rate-hz", sim.accelerometer.rate_hz, 0.0, 100000.0);
    sim.accelerometer.noise_rms =
        read.number("accelerometer-noise", sim.accelerometer.noise_rms, 0.0, 1000.0);
    sim.accelerometer.peak_accel =
        read.number("accelerometer-peak", sim.accelerometer.peak_accel, 0.001, 1000.0);
}

}  // namespace

actuator::Declaration undeclared_sim_actuator() {
    // The declaration's own defaults (actuator/declaration.hpp): one set of numbers.
    actuator::Declaration declaration;
    declaration.kind = Kind::lra;
    declaration.compensation = false;  // nothing is declared, so nothing is compensated
    return declaration;
}

SimActuator::SimActuator(SimSettings settings, MonotonicClock clock)
    : clock_(clock ? std::move(clock) : MonotonicClock(monotonic_now_ns)),
      settings_(settings),
      reverse_(settings.declared && settings.actuator.brake == actuator::Brake::reverse),
      model_(settings.truth.value_or(settings.actuator)) {
    if (settings.accelerometer.rate_hz > 0.0) {
        accelerometer_ = std::make_shared<SimAccelerometer>(
            settings.truth.value_or(settings.actuator), settings.accelerometer);
    }
    if (settings.trace) {
        trace_.emplace(*settings.trace);
    }
    if (settings.meter) {
        meter_ =
            std::make_unique<TerminalMeter>(settings.meter_fd, meter_label(settings.actuator.kind),
                                            TerminalMeter::glyphs_for_environment());
    }
}

bool SimActuator::take_declaration(const actuator::Declaration& declared) {
    if (!settings_.declared) {
        return false;  // it simulated its own [sim] model: a declaration now is another sim
    }
    const auto& running = settings_.actuator;
    if (declared.kind != running.kind || declared.brake != running.brake) {
        return false;
    }
    if (!settings_.truth) {
        // The new physics from now on, continuing the drive in force (the simulated state starts
        // again from rest: a sim's convenience, not a real actuator's).
        const std::int64_t now_ns = clock_();
        const actuator::Drive drive = model_.drive();
        actuator::Timeline fresh(declared);
        fresh.command(static_cast<double>(now_ns) * 1e-9, drive);
        model_ = std::move(fresh);
        if (accelerometer_) {
            // It feels the declared actuator too; a recording under way keeps the one it has.
            accelerometer_ = std::make_shared<SimAccelerometer>(declared, settings_.accelerometer);
            accelerometer_->command(now_ns, drive);
        }
    }
    settings_.actuator = declared;
    return true;
}

Capabilities SimActuator::capabilities() const {
    Capabilities capabilities;
    capabilities.amplitude_control = true;
    capabilities.frequency_control = true;
    capabilities.effect_memory = false;
    capabilities.reverse = reverse_;
    return capabilities;
}

void SimActuator::take(double amplitude, double frequency_hz) {
    const std::int64_t now_ns = clock_();
    const double t_s = static_cast<double>(now_ns) * 1e-9;
    // The strength is continuous, so its value at the command instant is the same before and
    // after it: how far the actuator got with the previous drive.
    const double response = model_.response_at(t_s);
    model_.command(t_s, {amplitude, frequency_hz});
    if (accelerometer_) {
        accelerometer_->command(now_ns, {amplitude, frequency_hz});
    }
    ++commands_;
    if (meter_) {
        // The meter shows where the actuator is heading (rest, while braking); an ERM has no
        // frequency to show.
        const bool erm = model_.physics().declaration().kind == Kind::erm;
        const double shown_hz =
            erm ? -1.0 : model_.physics().frequency_of({amplitude, frequency_hz});
        meter_->show(amplitude > 0.0 ? model_.target() : 0.0, shown_hz);
    }
    if (trace_) {
        trace_->record(now_ns, amplitude, frequency_hz, response);
    }
}

void SimActuator::apply(const Drive& drive) {
    const double lowest = reverse_ ? -1.0 : 0.0;
    const double amplitude =
        std::isnan(drive.amplitude) ? 0.0 : std::clamp(drive.amplitude, lowest, 1.0);
    const double frequency_hz =
        std::isfinite(drive.frequency_hz) && drive.frequency_hz > 0.0 ? drive.frequency_hz : 0.0;
    try {
        take(amplitude, frequency_hz);
    } catch (const std::runtime_error& error) {
        throw DeviceError(error.what());
    }
}

void SimActuator::off() noexcept {
    try {
        take(0.0, 0.0);
    } catch (const std::exception& error) {
        // off() runs on every error path; one warning is enough to say the trace is incomplete.
        if (!trace_failure_logged_) {
            trace_failure_logged_ = true;
            log::warning(std::string("sim actuator: ") + error.what() +
                         " (further trace errors on off() are not logged)");
        }
    } catch (...) {
        // Nothing else in take() is expected to throw; off() must not, whatever happens.
    }
}

std::unique_ptr<Actuator> make_sim_actuator(const std::map<std::string, std::string>& settings,
                                            const std::optional<actuator::Declaration>& declared) {
    DriverSettings read("sim", settings);
    SimSettings sim;
    if (declared) {
        for (const char* key : kModelKeys) {
            if (read.has(key)) {
                throw SettingError(key, std::string("sim setting ") + key + " = \"" +
                                            settings.at(key) +
                                            "\": the actuator is declared in [actuator], and the "
                                            "sim simulates that one (declare it there only)");
            }
        }
        sim.actuator = *declared;
        sim.declared = true;
    } else {
        read_model(read, settings, sim.actuator);
    }
    read_truth(read, sim);
    if (auto trace = read.text("trace")) {
        sim.trace = *trace;
    }
    sim.meter = read.flag("meter", sim.meter);
    read.reject_unknown();
    return std::make_unique<SimActuator>(std::move(sim));
}

}  // namespace vibscore::drivers
