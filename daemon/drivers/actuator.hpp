#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "actuator/declaration.hpp"
#include "common/device_error.hpp"

namespace vibscore::sensors {
class Accelerometer;
}

namespace vibscore::drivers {

// The device failed or went away: what apply() and the backends throw. One type with the editor's
// keys (common/), so the player and the bus adaptor catch it by this name.
using vibscore::DeviceError;

// What an actuator backend can do; the player adapts what it sends to it.
struct Capabilities {
    bool amplitude_control = true;   // strength can vary, not only on/off
    bool frequency_control = false;  // the vibration frequency can be chosen per note
    bool effect_memory = false;      // effects can be uploaded ahead of their onset (prepare)
    bool envelopes = false;          // a linear ramp can be handed over whole (Drive::ramp_s)
    bool gain_control = false;       // the device scales every drive itself (set_gain)
    // The backend can drive backwards: a negative amplitude reverses an ERM (an H-bridge) or
    // drives an LRA in anti-phase. Without it a negative amplitude counts as 0.
    bool reverse = false;
    double max_on_time_s = 0.0;  // longest continuous drive allowed; 0 = no limit
    // The kernel switches the actuator off by itself after the time set_off_timer() gave, so a
    // note ends even when the daemon dies in it. Not one of the D-Bus names.
    bool off_timer = false;
    // Without amplitude control, strength is the on-time within each period this long.
    double pulse_period_s = 0.040;

    // The names the D-Bus Capabilities property lists: "amplitude-control", ...
    std::vector<std::string> names() const;
};

// One instruction: from now on vibrate with this strength and frequency.
struct Drive {
    // -1..1 of the backend's full drive; 0 is off. Negative only for backends with the reverse
    // capability: reverse polarity (ERM) or anti-phase (LRA), as the renderer brakes with it.
    double amplitude = 0.0;
    double frequency_hz = 0.0;  // 0: the actuator's own (an ERM's, or an LRA's resonance)
    // Only for backends with envelopes: the strength moves linearly from `amplitude` to
    // `ramp_to` over `ramp_s` seconds and then holds there. ramp_s = 0: no ramp.
    double ramp_to = 0.0;
    double ramp_s = 0.0;
    bool operator==(const Drive&) const = default;
};

// The narrow interface between the player and an actuator backend. Calls come from the daemon's
// playback thread (one thread at a time) and must return quickly (no sleeping).
class Actuator {
  public:
    virtual ~Actuator() = default;

    virtual std::string_view driver_name() const = 0;
    virtual Capabilities capabilities() const = 0;

    // Applies the drive at once. Throws DeviceError when the device fails.
    virtual void apply(const Drive& drive) = 0;

    // Stops vibrating at once. Never throws: it is called on every error and shutdown path.
    virtual void off() noexcept = 0;

    // Backends with effect memory load the drive that comes next, ahead of its onset, so that
    // apply(next) then costs one write. Called after each apply; may be ignored.
    virtual void prepare(const Drive& /*next*/) {}

    // Backends with an off timer: the player calls this before each apply() that switches on,
    // with the time the schedule keeps the actuator on from then (at most max_on_time_s), and
    // the backend arms the kernel's timer with it.
    virtual void set_off_timer(double /*seconds*/) {}

    // Backends with gain control scale every drive by `gain` (0..1, the master intensity) in
    // the device; the player then leaves the master intensity out of the drives it sends.
    virtual void set_gain(double /*gain*/) {}

    // A sensor that feels this actuator's vibration and comes with the backend (the sim's model
    // of one), for `vibscore calibrate` when [calibration] names no device; nullptr for most.
    virtual std::shared_ptr<sensors::Accelerometer> accelerometer() const { return nullptr; }

    // The board's actuator was declared anew ([actuator] changed on a reload). A backend made of
    // the declaration (the sim simulates it) takes the new one in place and returns true, so
    // what plays goes on; false: its capabilities would change, so it must be reopened. A real
    // backend drives whatever is on the board: nothing to take, true.
    virtual bool take_declaration(const actuator::Declaration& /*declared*/) { return true; }
};

}  // namespace vibscore::drivers
