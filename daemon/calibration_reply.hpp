#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <exception>
#include <map>
#include <string>

#include "daemon/calibrator.hpp"

namespace vibscore::daemon {

using CalibrationReply = std::map<std::string, sdbus::Variant>;

// Calibrate's options (dbus/org.vibscore.Haptics1.xml): "apply" and "recording", both b.
// Throws RequestError (invalid) naming an unknown option or one of the wrong type.
struct CalibrateOptions {
    bool apply = false;
    bool recording = false;
};
CalibrateOptions parse_calibrate_options(const std::map<std::string, sdbus::Variant>& options);

// Calibrate's result dictionary for an outcome; with `recording`, the plan and the recording too.
CalibrationReply calibration_reply(const CalibrationOutcome& outcome, bool recording);

// What a calibration that failed answers: CalibrationRefused as NoAccelerometer, Untrusted or
// Busy (cut short); std::invalid_argument as InvalidDocument; a reader's std::runtime_error as
// Device; the rest as the bus boundary maps them (bus_errors.hpp). Always throws.
[[noreturn]] void throw_calibration_error(const std::exception_ptr& error);

}  // namespace vibscore::daemon
