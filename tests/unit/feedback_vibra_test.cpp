// feedbackd 0.8.2's vibra feedbacks as patterns (fbd-feedback-vibra-{rumble,periodic,pattern}.c):
// rumbles with their pauses and feedbackd's corner cases, the periodic effect's fade-in, patterns,
// and the maximum haptic strength.
#include <gtest/gtest.h>

#include "feedback/vibra_feedback.hpp"

namespace vibscore::feedback {
namespace {

// Patterns equal to a nanosecond and a billionth of full strength.
::testing::AssertionResult same(const VibrationPattern& actual, const VibrationPattern& expected) {
    auto text = [](const VibrationPattern& pattern) {
        std::string out;
        for (const auto& step : pattern) {
            out += "{" + std::to_string(step.seconds) + " s, " + std::to_string(step.from) +
                   " -> " + std::to_string(step.to) + "} ";
        }
        return out;
    };
    bool equal = actual.size() == expected.size();
    for (std::size_t i = 0; equal && i < actual.size(); ++i) {
        equal = std::abs(actual[i].seconds - expected[i].seconds) < 1e-9 &&
                std::abs(actual[i].from - expected[i].from) < 1e-9 &&
                std::abs(actual[i].to - expected[i].to) < 1e-9 &&
                actual[i].frequency_hz == expected[i].frequency_hz;
    }
    if (equal) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got " << text(actual) << "\nwanted " << text(expected);
}

PatternStep on(double seconds, double strength) {
    return {seconds, strength, strength, 0.0};
}
PatternStep off(double seconds) {
    return {seconds, 0.0, 0.0, 0.0};
}

TEST(ARumble, PlaysCountRumblesOfTheDurationSharedLessThePause) {
    // message-new-sms: 500 ms in two, 100 ms pauses; feedbackd's default magnitude 0.5.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(500, 2, 100)),
                     {on(0.15, 0.5), off(0.1), on(0.15, 0.5), off(0.1)}));
    // What the division leaves over is silence, so a loop repeats every `duration`.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(100, 3, 0, 0.8)),
                     {on(0.033, 0.8), on(0.033, 0.8), on(0.033, 0.8), off(0.001)}));
}

TEST(ARumble, WithNothingLeftForTheRumbleIsCutShortByTheFeedbacksEnd) {
    // Exactly nothing left: feedbackd's 1000 ms fallback, cut at the duration.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(100, 2, 50)), {on(0.1, 0.5)}));
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(3000, 1, 3000)), {on(1.0, 0.5), off(2.0)}));
    // Less than nothing wraps around in feedbackd's unsigned arithmetic: a rumble its duration
    // timer ends.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(100, 2, 51)), {on(0.1, 0.5)}));
    // One millisecond left is a rumble.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(102, 2, 50)),
                     {on(0.001, 0.5), off(0.05), on(0.001, 0.5), off(0.05)}));
    EXPECT_TRUE(vibra_pattern(rumble_feedback(0, 1, 0)).empty());
}

TEST(APeriodicFeedback, FadesInFromItsLevelOverItsTimeAsFeedbackd08Does) {
    // trixie's phone-incoming-call: magnitude 0.5, 1000 ms, the defaults fade-in-level 0 and
    // fade-in-time 500.
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 0.5, 0.0, 500)),
                     {{0.5, 0.0, 0.5, 0.0}, on(0.5, 0.5)}));
    // No fade-in time: the magnitude from the start.
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 0.5, 0.2, 0)), {on(1.0, 0.5)}));
    // A fade-in longer than the effect is cut where the effect ends.
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 1.0, 0.0, 2000)), {{1.0, 0.0, 0.5, 0}}));
    // Exactly as long: the ramp reaches the magnitude at the end.
    EXPECT_TRUE(
        same(vibra_pattern(periodic_feedback(1000, 1.0, 0.25, 1000)), {{1.0, 0.25, 1.0, 0}}));
}

TEST(TheMaximumHapticStrength, CapsEveryMagnitudeAndKeepsAFadeInsRatio) {
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(500, 2, 100, 0.8), 0.3),
                     {on(0.15, 0.3), off(0.1), on(0.15, 0.3), off(0.1)}));
    // A maximum at or above the magnitude changes nothing.
    EXPECT_TRUE(same(vibra_pattern(rumble_feedback(15, 1, 0, 0.8), 0.8), {on(0.015, 0.8)}));
    // Periodic: magnitude 0.8 capped at 0.4, its fade-in from 0.4 (half of it) from 0.2.
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 0.8, 0.4, 500), 0.4),
                     {{0.5, 0.2, 0.4, 0}, on(0.5, 0.4)}));
    // A fade-in level above the magnitude keeps the ratio, but not past the maximum (where
    // feedbackd would start at 0.5).
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 0.5, 1.0, 500), 0.25),
                     {on(0.5, 0.25), on(0.5, 0.25)}));
    EXPECT_TRUE(same(vibra_pattern(periodic_feedback(1000, 0.5, 1.0, 500), 0.75),
                     {{0.5, 0.75, 0.5, 0}, on(0.5, 0.5)}));
    EXPECT_TRUE(same(vibra_pattern(pattern_feedback({{1.0, 200}, {0.0, 200}, {0.2, 100}}), 0.5),
                     {on(0.2, 0.5), off(0.2), on(0.1, 0.2)}));
    EXPECT_TRUE(vibra_pattern(rumble_feedback(500, 1, 0), 0.0) == (VibrationPattern{on(0.5, 0.0)}));
}

TEST(APattern, PlaysItsStepsAndLastsTheirSum) {
    const auto feedback = pattern_feedback({{0.25, 50}, {0.0, 250}, {0.25, 50}, {1.0, 0}});
    EXPECT_EQ(feedback.duration_ms, 350u);
    // A step of no time is left out.
    EXPECT_TRUE(same(vibra_pattern(feedback), {on(0.05, 0.25), off(0.25), on(0.05, 0.25)}));
    EXPECT_TRUE(vibra_pattern(pattern_feedback({})).empty());
}

}  // namespace
}  // namespace vibscore::feedback
