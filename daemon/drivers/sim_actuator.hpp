#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "common/monotonic_clock.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/actuator_model.hpp"
#include "daemon/drivers/terminal_meter.hpp"
#include "daemon/drivers/trace_file.hpp"

namespace vibscore::drivers {

struct SimSettings {
    ModelSettings model;
    std::optional<std::filesystem::path> trace;  // CSV of every command, when set
    bool meter = false;                          // draw a live meter on meter_fd
    int meter_fd = 2;
};

// Monotonic time in nanoseconds: monotonic_now_ns, or a test's clock.
using MonotonicClock = std::function<std::int64_t()>;

// An actuator that exists only as a model: the default on a development machine. It records what
// it is told (trace file), shows it (terminal meter) and models what a real ERM or LRA would do
// with it (model()).
class SimActuator : public Actuator {
  public:
    // Throws std::runtime_error naming the trace path when the trace file cannot be created, and
    // std::invalid_argument for impossible model constants.
    explicit SimActuator(SimSettings settings, MonotonicClock clock = monotonic_now_ns);

    std::string_view driver_name() const override { return "sim"; }
    Capabilities capabilities() const override;

    // Amplitude is clamped to 0..1 (NaN counts as 0); a negative or non-finite frequency counts
    // as 0, the actuator's own. Throws DeviceError naming the trace path when the trace write
    // fails; the model and the meter have already taken the command by then.
    void apply(const Drive& drive) override;
    void off() noexcept override;

    const ActuatorModel& model() const { return model_; }
    // Commands taken so far, apply() and off() alike.
    std::uint64_t command_count() const { return commands_; }

  private:
    void take(double amplitude, double frequency_hz);

    MonotonicClock clock_;
    ActuatorModel model_;
    std::optional<TraceFile> trace_;
    std::unique_ptr<TerminalMeter> meter_;
    std::uint64_t commands_ = 0;
    bool trace_failure_logged_ = false;
};

// Builds a SimActuator from the string settings of the daemon's configuration:
//   model         erm | lra (default lra)
//   resonance-hz  LRA resonance f0 (default 175)
//   q             LRA quality factor (default 8)
//   spin-up-ms    ERM spin-up time constant (default 50)
//   spin-down-ms  ERM spin-down time constant (default 80)
//   trace         path of a CSV trace of every command (default none)
//   meter         true | false: live meter on stderr (default false)
// Throws std::invalid_argument naming the key and the value for an invalid value or an unknown
// key, and std::runtime_error when the trace file cannot be created.
std::unique_ptr<Actuator> make_sim_actuator(const std::map<std::string, std::string>& settings);

}  // namespace vibscore::drivers
