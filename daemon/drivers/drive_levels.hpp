#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "daemon/drivers/actuator.hpp"

// How the PWM and sysfs backends read a Drive: the same limits for every one of them.
namespace vibscore::drivers {

// The range of frequencies an LRA backend drives; a drive outside it is held at the nearer end.
constexpr double kMinLraHz = 10.0;
constexpr double kMaxLraHz = 1000.0;

// The drive's amplitude within 0..1; NaN counts as 0 (off).
inline double drive_amplitude(const Drive& drive) {
    return drive.amplitude > 0.0 ? std::min(drive.amplitude, 1.0) : 0.0;
}

// How much of each half period an LRA's pulse lasts for a drive of this amplitude (its sign
// aside): the LRA's resonance responds to the pulses' fundamental, and a pulse d x T/2 wide has
// sin(pi d / 2) of the full square wave's, so d = (2 / pi) asin(|amplitude|) makes the strength
// proportional to the amplitude, as the actuator model (and a sine clef's A) mean it.
inline double lra_pulse_share(double amplitude) {
    const double a = std::isfinite(amplitude) ? std::min(std::abs(amplitude), 1.0) : 0.0;
    return 2.0 / std::numbers::pi * std::asin(a);
}

// The frequency to drive an LRA at: the drive's own, or the resonance when the drive leaves the
// choice to the actuator (0, negative or not finite).
inline double lra_frequency_hz(const Drive& drive, double resonance_hz) {
    const bool own = std::isfinite(drive.frequency_hz) && drive.frequency_hz > 0.0;
    return std::clamp(own ? drive.frequency_hz : resonance_hz, kMinLraHz, kMaxLraHz);
}

}  // namespace vibscore::drivers
