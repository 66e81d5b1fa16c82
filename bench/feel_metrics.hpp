#pragma once

#include <functional>
#include <string>
#include <vector>

#include "daemon/render/performance.hpp"

// What bench/feel measures of a produced strength against the written one (docs/performance.md,
// "What people feel"). Strengths are sampled alike, at `rate_hz` from time 0.
namespace vibscore::bench {

struct NoteSpan {
    double onset = 0.0, end = 0.0;  // written sounding time
    double peak = 0.0;              // the written strength at its strongest
    bool tied_to_next = false;      // legato or portamento: no silence before the next note
};

// The notes of a performance, strength x scale.
std::vector<NoteSpan> note_spans(const render::Performance& performance, double scale);

struct ScoreFeel {
    std::string name;
    int notes = 0;
    // Notes whose produced strength reaches 90 % of their written peak while they sound.
    int reached = 0;
    // Per note: note start -> 90 % of its written peak, ms (INFINITY: never while it sounds).
    std::vector<double> onsets_ms;
    // Per note followed by silence: written end -> below 10 % of its written peak, ms, as if the
    // silence lasted (the drives up to the next note's start only).
    std::vector<double> stops_ms;
    // Silences between notes, and those felt: the produced strength dips between the two notes'
    // peaks to at most half the weaker peak.
    int silences = 0, felt = 0;
    // The integral of |produced - written| over that of written, the ringing after the end too.
    double envelope_error = 0.0;
    // Artefacts (issue 32), as fractions of a note's written peak. Rebound: after a note followed
    // by silence has fallen below 10 % of its peak, the most its strength rises again (the drives
    // up to the next note's start only); 0 when it never rises. Overshoot: the most the strength
    // goes above the peak while the note sounds, for notes that start below their peak (a tied
    // note after a stronger one starts above it by the score's will).
    double max_rebound = 0.0;
    double max_overshoot = 0.0;
};

// `produced` is what the actuator makes of the score; `produced_until(t)` what it makes of the
// drives sent before t only (for the stops).
ScoreFeel measure(const std::string& name, const std::vector<NoteSpan>& notes,
                  const std::vector<double>& written, const std::vector<double>& produced,
                  const std::function<std::vector<double>(double)>& produced_until, double rate_hz);

// The median, INFINITY counting as the largest value; NaN for none.
double median(std::vector<double> values);

// bench/feel's figures of one actuator, pooled over the pieces it played (docs/performance.md,
// "What people feel"): the counts summed; onset and stop the medians over every note of every
// piece (a person feels notes, not pieces); the envelope error the median of the pieces'; rebound
// and overshoot the most of any piece.
struct Pooled {
    int notes = 0, reached = 0, silences = 0, felt = 0;
    double onset_ms = 0, stop_ms = 0, error = 0;  // medians
    double rebound = 0, overshoot = 0;            // the most over the pieces
};
Pooled pool(const std::vector<ScoreFeel>& scores);

}  // namespace vibscore::bench
