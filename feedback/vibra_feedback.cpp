#include "feedback/vibra_feedback.hpp"

#include <algorithm>

namespace vibscore::feedback {

namespace {

void add(VibrationPattern& pattern, unsigned ms, double from, double to) {
    if (ms > 0) {
        pattern.push_back({ms / 1000.0, from, to, 0.0});
    }
}

VibrationPattern rumble(const VibraFeedback& feedback, double max_strength) {
    const double strength = std::min(feedback.magnitude, max_strength);
    const unsigned count = std::max(feedback.count, 1u);
    const unsigned period = feedback.duration_ms / count;
    VibrationPattern pattern;
    if (period <= feedback.pause_ms) {
        // feedbackd: rumble = period - pause in unsigned arithmetic; exactly 0 falls back to
        // 1000 ms, less wraps around; either way its duration timer ends the feedback.
        const unsigned ms = period == feedback.pause_ms
                                ? std::min(kDefaultVibraMs, feedback.duration_ms)
                                : feedback.duration_ms;
        add(pattern, ms, strength, strength);
        add(pattern, feedback.duration_ms - ms, 0.0, 0.0);
        return pattern;
    }
    for (unsigned i = 0; i < count; ++i) {
        add(pattern, period - feedback.pause_ms, strength, strength);
        add(pattern, feedback.pause_ms, 0.0, 0.0);
    }
    add(pattern, feedback.duration_ms - count * period, 0.0, 0.0);
    return pattern;
}

VibrationPattern periodic(const VibraFeedback& feedback, double max_strength) {
    // fbd_feedback_vibra_periodic_start_vibra: the fade-in level keeps its ratio to the
    // magnitude when the maximum strength lowers it. feedbackd lets a fade-in level above the
    // magnitude exceed the maximum; here the maximum holds for it too.
    const double magnitude = std::min(feedback.magnitude, max_strength);
    const double kept = feedback.magnitude > 0.0
                            ? std::min(magnitude * feedback.fade_in_level / feedback.magnitude,
                                       feedback.fade_in_level)
                            : feedback.fade_in_level;
    const double start = std::min(kept, max_strength);
    const unsigned duration = feedback.duration_ms;
    const unsigned attack = feedback.fade_in_time_ms;
    VibrationPattern pattern;
    if (attack > 0) {
        // The kernel's envelope: linear from the attack level to the magnitude, cut off where
        // the effect ends.
        const unsigned ms = std::min(attack, duration);
        add(pattern, ms, start, start + (magnitude - start) * ms / attack);
    }
    if (duration > attack) {
        add(pattern, duration - attack, magnitude, magnitude);
    }
    return pattern;
}

}  // namespace

VibraFeedback rumble_feedback(unsigned duration_ms, unsigned count, unsigned pause_ms,
                              double magnitude) {
    VibraFeedback feedback;
    feedback.type = VibraFeedback::Type::rumble;
    feedback.duration_ms = duration_ms;
    feedback.count = count;
    feedback.pause_ms = pause_ms;
    feedback.magnitude = magnitude;
    return feedback;
}

VibraFeedback periodic_feedback(unsigned duration_ms, double magnitude, double fade_in_level,
                                unsigned fade_in_time_ms) {
    VibraFeedback feedback;
    feedback.type = VibraFeedback::Type::periodic;
    feedback.duration_ms = duration_ms;
    feedback.magnitude = magnitude;
    feedback.fade_in_level = fade_in_level;
    feedback.fade_in_time_ms = fade_in_time_ms;
    return feedback;
}

VibraFeedback pattern_feedback(std::vector<VibraStep> steps) {
    VibraFeedback feedback;
    feedback.type = VibraFeedback::Type::pattern;
    feedback.duration_ms = 0;
    for (const auto& step : steps) {
        feedback.duration_ms += step.ms;
    }
    feedback.steps = std::move(steps);
    return feedback;
}

VibrationPattern vibra_pattern(const VibraFeedback& feedback, double max_strength) {
    switch (feedback.type) {
        case VibraFeedback::Type::rumble:
            return rumble(feedback, max_strength);
        case VibraFeedback::Type::periodic:
            return periodic(feedback, max_strength);
        case VibraFeedback::Type::pattern:
            break;
    }
    VibrationPattern pattern;
    for (const auto& step : feedback.steps) {
        const double strength = std::min(step.magnitude, max_strength);
        add(pattern, step.ms, strength, strength);
    }
    return pattern;
}

}  // namespace vibscore::feedback
