#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "actuator/timeline.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/sim_accelerometer.hpp"
#include "daemon/drivers/terminal_meter.hpp"
#include "daemon/drivers/trace_file.hpp"

namespace vibscore::drivers {

// The actuator [sim] simulates when vibscored.conf declares none ([actuator] absent) and [sim]
// sets no model: an LRA with the declaration's defaults (175 Hz, Q 15; an ERM: spin-up 40 ms,
// spin-down 80 ms), strength 1 at full drive, uncompensated.
actuator::Declaration undeclared_sim_actuator();

struct SimSettings {
    actuator::Declaration actuator = undeclared_sim_actuator();
    // The actuator is the one [actuator] declares: its brake says whether the simulated board
    // has an H-bridge (the reverse-drive capability).
    bool declared = false;
    // The actuator as it truly is, when it should differ from what is declared ([sim] true-*):
    // what the model and the accelerometer simulate. nullopt: the declared one.
    std::optional<actuator::Declaration> truth;
    // The sim's accelerometer ([sim] accelerometer-*); rate 0: none.
    actuator::SensorOptions accelerometer;
    std::optional<std::filesystem::path> trace;  // CSV of every drive as sent, when set
    bool meter = false;                          // draw a live meter on meter_fd
    int meter_fd = 2;
};

// Monotonic time in nanoseconds: monotonic_now_ns, or a test's clock.
using MonotonicClock = std::function<std::int64_t()>;

// An actuator that exists only as a model: the default on a development machine. It records what
// it is told (trace file: every drive as sent, its amplitude -1..1 with negative = reverse or
// anti-phase, and its frequency), shows it (terminal meter) and simulates what the declared ERM
// or LRA does with it (model()): spin-up, coasting and reverse drive of an ERM, the resonance of
// an LRA building up, ringing down and pushed down by anti-phase drive.
class SimActuator : public Actuator {
  public:
    // Throws std::runtime_error naming the trace path when the trace file cannot be created, and
    // std::invalid_argument for impossible constants.
    explicit SimActuator(SimSettings settings, MonotonicClock clock = monotonic_now_ns);

    std::string_view driver_name() const override { return "sim"; }
    Capabilities capabilities() const override;

    // Amplitude is clamped to -1..1 (0..1 without the reverse-drive capability; NaN counts as 0);
    // a negative or non-finite frequency counts as 0, the actuator's own. Throws DeviceError
    // naming the trace path when the trace write fails; the model and the meter have already
    // taken the drive by then.
    void apply(const Drive& drive) override;
    void off() noexcept override;
    std::shared_ptr<sensors::Accelerometer> accelerometer() const override {
        return accelerometer_;
    }

    // In place when only the numbers changed: the same kind and brake (the reverse-drive
    // capability the player planned with); the model (and the accelerometer's, unless [sim]
    // true-* keys say how the actuator truly is) then simulates the new declaration from the
    // drive in force. Else false (reopen).
    bool take_declaration(const actuator::Declaration& declared) override;

    const actuator::Timeline& model() const { return model_; }
    // Commands taken so far, apply() and off() alike.
    std::uint64_t command_count() const { return commands_; }

  private:
    void take(double amplitude, double frequency_hz);

    MonotonicClock clock_;
    SimSettings settings_;
    bool reverse_;
    actuator::Timeline model_;
    std::optional<TraceFile> trace_;
    std::unique_ptr<TerminalMeter> meter_;
    std::uint64_t commands_ = 0;
    bool trace_failure_logged_ = false;
    std::shared_ptr<SimAccelerometer> accelerometer_;
};

// Builds a SimActuator from the string settings of the daemon's configuration:
//   trace         path of a CSV trace of every drive (default none)
//   meter         true | false: live meter on stderr (default false)
// and, only when no actuator is declared ([actuator] absent), the simulated actuator's own, as
// [actuator] would declare it (the same keys, defaults and limits, actuator/declaration.hpp):
//   model         erm | lra (default lra): [actuator]'s kind
//   resonance-hz, q          an LRA's (default 175, 15)
//   spin-up-ms, spin-down-ms an ERM's (default 40, 80)
// a key of the other model being refused, as in [actuator];
// and, declared or not, how the simulated actuator truly is when it should differ (what
// `vibscore calibrate` then measures): true-resonance-hz, true-q, true-spin-up-ms,
// true-spin-down-ms (default: as declared), and its accelerometer: accelerometer-rate-hz
// (default 1000; 0: none), accelerometer-noise (m/s² RMS per axis, default 0.02),
// accelerometer-peak (m/s² at full drive, default 10).
// With `declared`, the sim simulates that actuator, and those five keys are refused: the physics
// is declared once. Throws SettingError naming the key and the value for an invalid value or an
// unknown key, and std::runtime_error when the trace file cannot be created.
std::unique_ptr<Actuator> make_sim_actuator(
    const std::map<std::string, std::string>& settings,
    const std::optional<actuator::Declaration>& declared = std::nullopt);

}  // namespace vibscore::drivers
