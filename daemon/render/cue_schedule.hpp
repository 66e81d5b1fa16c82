#pragma once

#include <cstddef>
#include <vector>

#include "daemon/render/performance.hpp"

namespace vibscore::render {

// One thing the player does at one instant of a performance.
struct Cue {
    enum class Kind { drive, position };

    double at = 0.0;  // seconds from the start of the performance
    Kind kind = Kind::drive;
    // drive: from now on vibrate this strongly (clef units, >= 0) at this frequency (0 for
    // curve and line clefs, whose waveform already is the drive level).
    double amplitude = 0.0;
    double frequency_hz = 0.0;
    // drive, only after adapt_cues() for backends with envelopes: the strength moves linearly
    // to ramp_to over ramp_s seconds (0: no ramp) and holds there until the next drive.
    double ramp_to = 0.0;
    double ramp_s = 0.0;
    // position: the note or rest that begins now.
    std::size_t bar = 0, symbol = 0;
};

struct CueOptions {
    // Changing strength (crescendo, portamento, curve waveforms) is followed in steps this far
    // apart at most; steps in line waveforms fall exactly on their points.
    double update_interval_s = 0.005;
};

// The performance as actuator commands (no backend takes a sample stream): a drive at each note
// onset, updates along ramps and shapes, a drive of 0 when a note ends, and a position cue at
// each note or rest. Cues are in time order; a drive equal to the one before is left out.
std::vector<Cue> cue_schedule(const Performance& performance, const CueOptions& options = {});

}  // namespace vibscore::render
