#pragma once

#include <stdexcept>

namespace vibscore {

// A device failed or went away: an actuator the daemon drives, or the keys the editor reads.
// The message names the device and the errno text.
class DeviceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace vibscore
