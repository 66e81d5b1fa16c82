#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "actuator/calibration.hpp"
#include "actuator/declaration.hpp"

namespace vibscore::client {

// vibscore calibrate: measuring the actuator with an accelerometer (docs/drivers.md,
// "Calibrating"). Offline, for any recorder: --plan writes the probe, --estimate reads a
// recording of it. Live, through vibscored: calibrate_live (client/calibrate_live.cpp).
struct CalibrateRequest {
    bool plan = false;                  // --plan
    std::vector<std::string> estimate;  // --estimate PLAN.csv ACCEL.csv
    std::string kind;                   // --kind erm|lra ("": the --actuator file's)
    std::string actuator_file;          // --actuator FILE: the nominal declaration
    std::string output;                 // -o PLAN.csv
    bool apply = false;                 // live only
    std::string png, svg;               // the picture of the fit
};

// --plan: the probe for the kind as the sim trace's columns, to `request.output` (or `out` when
// it is "-"). exit_usage when neither --kind nor --actuator tells the kind.
int calibrate_plan(const CalibrateRequest& request, std::ostream& out, std::ostream& err);

// --estimate PLAN ACCEL: the [actuator] lines the recording gives, measured beside declared.
// exit_ok when the estimate is trusted; exit_failed with the reasons on `err` when not.
int calibrate_estimate(const CalibrateRequest& request, std::ostream& out, std::ostream& err);

// What an estimate says, as both paths print it: the [actuator] lines (declaration_lines) and,
// as `#` comments, each measured number beside the declared one. On `err`: what was not
// measured, and when not trusted, why.
// `declared_as` names where the declared numbers came from ("declared", or "in use" when an
// earlier calibration's are).
void print_estimate(const actuator::calibration::Estimate& estimate,
                    const std::optional<actuator::Declaration>& declared, std::ostream& out,
                    std::ostream& err, const std::string& declared_as = "declared");

// Before anything is measured: a --png/--svg name whose ending says no picture format is a
// usage error (exit_usage, said on `err`), not a failure after the probe.
int check_picture_names(const CalibrateRequest& request, std::ostream& err);

// The picture of a calibration (pictures::CalibrationPicture) to `path` (.png or .svg).
// Throws std::runtime_error / std::invalid_argument naming the file.
void write_calibration_picture(const std::string& path, const actuator::calibration::Plan& plan,
                               const std::vector<actuator::calibration::Sample>& samples,
                               const actuator::calibration::Estimate& estimate,
                               const std::optional<actuator::Declaration>& declared);

// `base` with every number the estimate measured in place of its own, trusted or not (for the
// picture of an estimate that was refused, and the table beside the declared numbers).
actuator::Declaration with_measured(actuator::Declaration base,
                                    const actuator::calibration::Estimate& estimate);

}  // namespace vibscore::client
