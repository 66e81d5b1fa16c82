// Patterns (held and ramped strengths, as force feedback and feedbackd give them) as scores:
// checked through the renderer's own strength at each instant, which is what the player plays.
#include <gtest/gtest.h>

#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/pattern_score.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using render::Performance;

Performance exact(const VibrationPattern& pattern) {
    return Performance(exact_pattern_score(pattern, "pattern", "<pattern>"));
}

// The shipped clef vibscore-feedback writes patterns on.
Clef pattern_ms_clef() {
    return load_clef_file(std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) /
                          "pattern-ms.clef.xml");
}

Performance on_clef(const ScoreOnClef& score) {
    const std::string clef_path =
        std::string(testing::required_env("VIBSCORE_CLEFS")) + "/pattern-ms.clef.xml";
    return Performance(testing::bundle_from(
        score.document, {{"pattern-ms.clef.xml", read_document_file(clef_path)}}));
}

TEST(ExactPatternScore, HeldStrengthsAndPausesKeepTheirExactTimes) {
    const VibrationPattern pattern{
        {0.015, 0.5, 0.5, 0.0}, {0.100, 0.0, 0.0, 0.0}, {0.0123, 1.0, 1.0, 0.0}};
    const auto performance = exact(pattern);
    EXPECT_DOUBLE_EQ(performance.duration(), 0.1273);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.0), 0.5);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.0149), 0.5);
    EXPECT_EQ(performance.envelope_at(0.0151), 0.0);
    EXPECT_EQ(performance.envelope_at(0.1149), 0.0);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.1151), 1.0);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.1272), 1.0);
}

TEST(ExactPatternScore, ConsecutiveStrengthsAreTiedSoNothingIsCutShort) {
    // Untied notes would lose the default silence at their ends; these jump without a gap.
    const auto performance = exact({{0.2, 1.0, 1.0, 0.0}, {0.2, 0.4, 0.4, 0.0}});
    for (double t = 0.0; t < 0.4; t += 0.001) {
        EXPECT_DOUBLE_EQ(performance.envelope_at(t), t < 0.2 ? 1.0 : 0.4) << t;
    }
}

TEST(ExactPatternScore, ARampIsLinearAndHoldsOnWhereItEnds) {
    // An FF attack: from 0.125 to 1 over 0.5 s, then held.
    const auto performance = exact({{0.5, 0.125, 1.0, 0.0}, {0.3, 1.0, 1.0, 0.0}});
    EXPECT_DOUBLE_EQ(performance.duration(), 0.8);
    for (double t = 0.0; t < 0.5; t += 0.01) {
        EXPECT_NEAR(performance.envelope_at(t), 0.125 + 0.875 * t / 0.5, 1e-9) << t;
    }
    EXPECT_NEAR(performance.envelope_at(0.6), 1.0, 1e-12);
}

TEST(ExactPatternScore, ARampIntoAPauseEndsAtItsLevel) {
    // An FF fade: from 0.8 down to 0.2 over 0.2 s, then nothing.
    const auto performance = exact({{0.2, 0.8, 0.2, 0.0}, {0.1, 0.0, 0.0, 0.0}});
    EXPECT_NEAR(performance.duration(), 0.3, 1e-12);
    EXPECT_NEAR(performance.envelope_at(0.1), 0.5, 1e-3);
    EXPECT_NEAR(performance.envelope_at(0.1998), 0.2, 1e-3);
    EXPECT_EQ(performance.envelope_at(0.25), 0.0);
}

TEST(ExactPatternScore, AFrequencyIsASineToneAndNoneIsTheActuatorsOwn) {
    const auto performance = exact({{0.1, 0.6, 0.6, 100.0}, {0.1, 0.6, 0.6, 0.0}});
    ASSERT_EQ(performance.tones().size(), 2u);
    EXPECT_EQ(performance.tones()[0].kind, render::Tone::Kind::sine);
    EXPECT_EQ(performance.tones()[0].frequency_start, 100.0);
    EXPECT_EQ(performance.tones()[1].kind, render::Tone::Kind::shape);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.15), 0.6);
}

TEST(ExactPatternScore, StretchesLongerThanAClefsTempoAreSplitWithoutAGap) {
    const auto performance = exact({{150.0, 0.7, 0.7, 0.0}});
    EXPECT_DOUBLE_EQ(performance.duration(), 150.0);
    EXPECT_EQ(performance.tones().size(), 3u);
    for (double t = 0.0; t < 150.0; t += 0.25) {
        EXPECT_DOUBLE_EQ(performance.envelope_at(t), 0.7) << t;
    }
}

TEST(ExactPatternScore, StretchesBelowAnEighthOfAMillisecondAreLeftOut) {
    const auto performance = exact({{0.00005, 1.0, 1.0, 0.0}, {0.0005, 0.3, 0.3, 0.0}});
    EXPECT_DOUBLE_EQ(performance.duration(), 0.0005);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.0001), 0.3);
}

TEST(PatternOnClef, TimesFallOnTheClefsMillisecondGridAndOneStrengthIsTheIntensity) {
    const Clef clef = pattern_ms_clef();
    ASSERT_EQ(clef.tempo, 0.008);
    // feedbackd's message-new-sms: two rumbles of 150 ms at 0x8000/0xffff, 100 ms apart.
    const double half = 32768.0 / 65535.0;
    const auto score = pattern_on_clef(
        {{0.15, half, half, 0}, {0.1, 0, 0, 0}, {0.15, half, half, 0}, {0.1, 0, 0, 0}}, "sms",
        "pattern-ms.clef.xml", clef);
    EXPECT_EQ(score.intensity, half);
    const auto performance = on_clef(score);
    EXPECT_DOUBLE_EQ(performance.duration(), 0.5);
    for (double t = 0.0005; t < 0.5; t += 0.001) {
        const bool on = t < 0.15 || (t > 0.25 && t < 0.4);
        EXPECT_DOUBLE_EQ(performance.envelope_at(t), on ? 1.0 : 0.0) << t;
    }
}

TEST(PatternOnClef, StrengthsAreTheNearestNinthOfTheStrongestOne) {
    const auto score = pattern_on_clef(
        {{0.004, 1.0, 1.0, 0}, {0.004, 0.6, 0.6, 0}, {0.004, 0.04, 0.04, 0}, {0.004, 0.3, 0.3, 0}},
        "steps", "pattern-ms.clef.xml", pattern_ms_clef());
    EXPECT_EQ(score.intensity, 1.0);
    const auto performance = on_clef(score);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.002), 1.0);
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.006), 0.5556);  // 5/9, the nearest to 0.6
    EXPECT_EQ(performance.envelope_at(0.010), 0.0);            // nearer to nothing than to 1/9
    EXPECT_DOUBLE_EQ(performance.envelope_at(0.014), 0.3333);
}

TEST(PatternOnClef, ARampIsAStaircaseThroughTheNumbersWithoutGaps) {
    // feedbackd's alarm-clock-elapsed fades in from 4096/32767 to full over 10 s.
    const auto score = pattern_on_clef({{10.0, 4096.0 / 32767.0, 1.0, 0}}, "alarm",
                                       "pattern-ms.clef.xml", pattern_ms_clef());
    const auto performance = on_clef(score);
    EXPECT_DOUBLE_EQ(performance.duration(), 10.0);
    double previous = 0.0;
    for (double t = 0.0005; t < 10.0; t += 0.001) {
        const double level = performance.envelope_at(t);
        const double wanted = 4096.0 / 32767.0 + (1.0 - 4096.0 / 32767.0) * t / 10.0;
        EXPECT_GE(level, previous) << t;
        EXPECT_NEAR(level, wanted, 1.0 / 18.0 + 1e-3) << t;
        previous = level;
    }
}

TEST(PatternOnClef, NothingToPlayIsAnEmptyScore) {
    const auto score =
        pattern_on_clef({{0.2, 0, 0, 0}}, "quiet", "pattern-ms.clef.xml", pattern_ms_clef());
    EXPECT_EQ(score.intensity, 1.0);
    EXPECT_EQ(on_clef(score).envelope_at(0.1), 0.0);
}

}  // namespace
}  // namespace vibscore
