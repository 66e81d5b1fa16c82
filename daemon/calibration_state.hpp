#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "actuator/calibration.hpp"
#include "actuator/declaration.hpp"

namespace vibscore::daemon {

struct DaemonConfig;

// The numbers `vibscore calibrate --apply` measured, kept in the daemon's state folder (the
// store) so they outlive restarts without anyone editing the administrator's vibscored.conf
// (docs/daemon.md, "Calibration"). Only the measured keys are kept; the rest of [actuator] stays
// as declared, and a measurement of another kind than the one declared is ignored.
struct MeasuredActuator {
    actuator::Kind kind = actuator::Kind::lra;
    std::optional<double> spin_up_s, spin_down_s;  // ERM
    std::optional<double> resonance_hz, q;         // LRA
    std::string measured_at;                       // ISO 8601 UTC, "2026-11-28T18:40:12Z"

    bool operator==(const MeasuredActuator&) const = default;
};

// The state file's name in the store. It starts with '.', so the registry never lists it.
inline constexpr const char* kCalibrationStateFile = ".actuator-calibration";

// What a trusted estimate measured, dated `measured_at`, rounded as the state file keeps it (five
// significant digits). Throws std::invalid_argument when a number is outside [actuator]'s limits.
MeasuredActuator measured_from(const actuator::calibration::Estimate& estimate,
                               std::string measured_at);

// The file's text, and back. parse_measured throws std::invalid_argument "file:line: ..." naming
// the key and value at fault (an unknown key, a number out of [actuator]'s limits, no kind, no
// date, a key of the other kind).
std::string measured_text(const MeasuredActuator& measured);
MeasuredActuator parse_measured(const std::string& text, const std::string& file);

// Writes the file atomically (common/atomic_file.hpp): after a crash at any instant the old
// measurement or the new one is there, never a mixture. Throws std::system_error naming the path.
void save_measured(const std::filesystem::path& file, const MeasuredActuator& measured);

// The measurement in `file`; nothing when there is none. A file that cannot be read or parsed is
// ignored with a log line saying why and how to fix it, and left where it is (it is never
// deleted: the administrator may want to look at it).
std::optional<MeasuredActuator> load_measured(const std::filesystem::path& file);

// `declared` with the measured numbers in place of its own (the other keys kept).
actuator::Declaration with_measured(actuator::Declaration declared,
                                    const MeasuredActuator& measured);

// "measured 2026-11-28T18:40:12Z": what the ActuatorSource property says of these numbers.
std::string measured_source(const MeasuredActuator& measured);

// After reading the configuration: the numbers in use are the declared ones, or the measured ones
// from the store's state file when it holds a measurement of the declared kind. Sets
// config.actuator (and [clefs] fit = auto's actuator with it) and config.actuator_source.
void use_measured_actuator(DaemonConfig& config);

// Now, as measured_at writes it.
std::string iso_utc_now();

}  // namespace vibscore::daemon
