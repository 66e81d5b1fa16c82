#pragma once

#include <ostream>

#include "client/calibrate_verb.hpp"

namespace vibscore::client {

// vibscore calibrate [--apply] [--png F|--svg F]: vibscored plays its probe on the actuator and
// records it with the accelerometer (Calibrate on the bus), and this prints what the estimate
// says as --estimate does. exit_ok when trusted (and with --apply, applied); exit_failed when
// refused or untrusted, with the reasons on `err`.
int calibrate_live(const CalibrateRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vibscore::client
