#pragma once

#include <optional>

#include "daemon/drivers/actuator.hpp"

namespace vibscore::daemon {

// How strongly a playback drives: its own intensity times the master Intensity, split between
// what the player multiplies into the strengths (`software`: the drives, or the pulses' duty on
// a backend without amplitude control, or the drives planned for a declared actuator) and what
// the device's gain does (`device_gain`, set when the backend has gain control).
struct StrengthScale {
    double software = 1.0;
    std::optional<double> device_gain;
};

// The one place that decides it, for planning a playback's cues and for each drive it sends.
// A probe (calibration) drives at full scale and full gain: it measures the actuator itself.
// A backend with gain control takes the master part as its gain, so the strengths (or the
// pulses' duty) carry only the playback's intensity: the model is linear, so drives planned
// without the master still follow the envelope once the device scales them, and pulses at full
// drive are scaled by the gain too (the master taken in both would be squared). Without gain
// control the strengths carry the master part.
inline StrengthScale strength_scale(const drivers::Capabilities& capabilities,
                                    double playback_intensity, double master_intensity,
                                    bool probe) {
    StrengthScale scale;
    if (capabilities.gain_control) {
        scale.device_gain = probe ? 1.0 : master_intensity;
    }
    if (probe) {
        scale.software = 1.0;
    } else if (capabilities.gain_control) {
        scale.software = playback_intensity;
    } else {
        scale.software = playback_intensity * master_intensity;
    }
    return scale;
}

}  // namespace vibscore::daemon
