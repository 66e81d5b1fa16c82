#pragma once

#include <string>
#include <vector>

#include "score/bundle.hpp"
#include "score/clef.hpp"

// Vibration patterns as the rest of Linux writes them (a force-feedback effect, a feedbackd
// theme entry, a Haptic.Vibrate call: strengths held or ramped for so many milliseconds) turned
// into scores, so that they play through the same renderer, arbitration and adaptation as any
// score does.
namespace vibscore {

// One stretch of a pattern: the strength moves linearly from `from` to `to` (0..1 of full
// drive) over `seconds`; 0 to 0 is a pause. frequency_hz 0 means the actuator's own frequency
// (an ERM's, an LRA's resonance), as a rumble motor has.
struct PatternStep {
    double seconds = 0.0;
    double from = 0.0;
    double to = 0.0;
    double frequency_hz = 0.0;

    bool operator==(const PatternStep&) const = default;
};

using VibrationPattern = std::vector<PatternStep>;

double pattern_seconds(const VibrationPattern& pattern);

// The pattern exactly, with clefs made for it: each stretch is one note in a bar of its own
// clef, whose tempo is the stretch's length and whose one number is its strength; a ramp is a
// portamento into a note at its final strength, consecutive stretches are tied, so nothing is
// cut short by the default silence between notes. Stretches under 0.125 ms are left out.
// Throws DocumentError when the result breaks a score limit (length, clefs, symbols).
ScoreBundle exact_pattern_score(const VibrationPattern& pattern, const std::string& title,
                                const std::string& file);

// The pattern on an existing clef (one a client can name in the registry but cannot change):
// times on its 32nd-note grid (tempo / 8), strengths relative to the pattern's strongest one
// and rounded to the nearest of the clef's numbers (or to a rest), a ramp as a staircase
// through those numbers, every sounding stretch tied by legato. `intensity` is that strongest
// strength, for the player to scale the whole score by, so a pattern of one strength plays it
// exactly. Frequencies are the clef's first string's.
struct ScoreOnClef {
    std::string document;  // a VibScore whose one clef is `clef_href`
    double intensity = 1.0;
};
ScoreOnClef pattern_on_clef(const VibrationPattern& pattern, const std::string& title,
                            const std::string& clef_href, const Clef& clef);

}  // namespace vibscore
