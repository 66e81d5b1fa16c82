#pragma once

#include <cstdint>
#include <vector>

#include "client/formats/score_builder.hpp"

// A strength envelope on the score's grid written as notes whose performance follows it.
// The renderer (daemon/render/performance.cpp) draws a crescendo from silence or from the
// crescendo before it, a decrescendo down to silence or to the decrescendo after it, and a
// portamento from one number to the next; a straight ramp between two other levels is none of
// these, so it is written as a glide that reaches its level one 32nd early (a short note at the
// end level) rather than dropped.
namespace vibscore::formats {

struct EnvelopePoint {
    std::int64_t tick = 0;
    double level = 0.0;  // 0..1 of the clef's strongest number
};

struct ShapedNotes {
    std::vector<GridNote> notes;     // touching, tied to one another; the last one takes `tie_out`
    double worst_level_error = 0.0;  // how far a level moved to reach a number (0..1)
    int early_ramps = 0;             // ramps that reach their level a 32nd early
    int pieces = 0;                  // the straight pieces of the envelope on the grid
};

// `points` in time order (two at one tick: a jump), the first at the note's start and the last
// at its end. `after_crescendo`: a crescendo note ends right where the first point is, so a
// crescendo here would go on from it.
ShapedNotes notes_for_envelope(std::vector<EnvelopePoint> points, int string, const Clef& clef,
                               bool after_crescendo, GridNote::Tie tie_out);

// The fraction (0..1) of the clef's strongest number that number `number` plays.
double number_level(const Clef& clef, int number);

}  // namespace vibscore::formats
