#pragma once

#include <vector>

#include "score/pattern_score.hpp"

// A vibra feedback as feedbackd 0.8.2 plays it (fbd-feedback-vibra-{rumble,periodic,pattern}.c,
// fbd-dev-vibra.c), and the pattern that is, so a feedbackd theme entry or a Haptic.Vibrate call
// plays as a score through vibscored. Every strength is 0..1 of full drive.
namespace vibscore::feedback {

// feedbackd's FBD_FEEDBACK_VIBRA_DEFAULT_DURATION, and its property defaults.
inline constexpr unsigned kDefaultVibraMs = 1000;
inline constexpr double kDefaultMagnitude = 0.5;
inline constexpr unsigned kDefaultFadeInMs = 500;

struct VibraStep {
    double magnitude = 0.0;  // 0 is a pause
    unsigned ms = 0;

    bool operator==(const VibraStep&) const = default;
};

struct VibraFeedback {
    enum class Type { rumble, periodic, pattern };
    Type type = Type::rumble;
    // How long the feedback lasts: feedbackd stops the vibra when it is over. A pattern's is the
    // sum of its steps.
    unsigned duration_ms = kDefaultVibraMs;
    double magnitude = kDefaultMagnitude;  // rumble and periodic
    // VibraRumble: `count` rumbles, each followed by `pause_ms`.
    unsigned count = 1;
    unsigned pause_ms = 0;
    // VibraPeriodic: the envelope's attack from fade_in_level up to magnitude.
    double fade_in_level = 0.0;
    unsigned fade_in_time_ms = kDefaultFadeInMs;
    // VibraPattern, and Haptic.Vibrate.
    std::vector<VibraStep> steps;

    bool operator==(const VibraFeedback&) const = default;
};

VibraFeedback rumble_feedback(unsigned duration_ms, unsigned count, unsigned pause_ms,
                              double magnitude = kDefaultMagnitude);
VibraFeedback periodic_feedback(unsigned duration_ms, double magnitude, double fade_in_level,
                                unsigned fade_in_time_ms);
VibraFeedback pattern_feedback(std::vector<VibraStep> steps);

// What the vibra does, no stronger than max_strength (feedbackd's max-haptic-strength: each
// magnitude is capped at it; a periodic fade-in keeps its ratio to the magnitude, and is capped
// too). The pattern
// lasts the feedback's duration, trailing silence included, so that a looping event repeats
// as feedbackd repeats it. Left out: feedbackd's 200 ms replay delay of a periodic effect (only
// a wait) and its 10 ms sine period (a memoryless vibra renders the carrier, not the wave).
//
// VibraRumble: rumbles of duration / count - pause ms. When nothing is left for the rumble,
// feedbackd's fallback (one 1000 ms rumble) or its unsigned wrap-around (a rumble far longer
// than the feedback) is cut short by the feedback's end: one rumble of at most the duration.
VibrationPattern vibra_pattern(const VibraFeedback& feedback, double max_strength = 1.0);

}  // namespace vibscore::feedback
