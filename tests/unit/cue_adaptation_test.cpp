#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>

#include "daemon/render/cue_adaptation.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

using testing::bundle_from;
using testing::one_clef_score;
using testing::sine_clef;

Cue drive(double at, double amplitude, double frequency_hz = 150.0) {
    Cue cue;
    cue.at = at;
    cue.amplitude = amplitude;
    cue.frequency_hz = frequency_hz;
    return cue;
}

Cue position(double at, std::size_t symbol) {
    Cue cue;
    cue.at = at;
    cue.kind = Cue::Kind::position;
    cue.symbol = symbol;
    return cue;
}

std::vector<Cue> drives(const std::vector<Cue>& cues) {
    std::vector<Cue> only;
    std::copy_if(cues.begin(), cues.end(), std::back_inserter(only),
                 [](const Cue& cue) { return cue.kind == Cue::Kind::drive; });
    return only;
}

// Total on-time of an on/off cue list between its first and last cue.
double on_time(const std::vector<Cue>& cues, double until) {
    double total = 0.0;
    for (std::size_t i = 0; i < cues.size(); ++i) {
        const double end = i + 1 < cues.size() ? cues[i + 1].at : until;
        if (cues[i].amplitude > 0.0) {
            total += end - cues[i].at;
        }
    }
    return total;
}

TEST(CueAdaptation, FrequencyIsDroppedForActuatorsWithoutFrequencyControl) {
    const auto adapted =
        adapt_cues({drive(0.0, 0.5, 150.0), drive(0.5, 0.5, 200.0), drive(1.0, 0.0)}, 1.0,
                   {.frequency = false});
    // Without its frequency the second drive says what the first does, so it goes.
    ASSERT_EQ(adapted.size(), 2u);
    EXPECT_EQ(adapted[0].frequency_hz, 0.0);
    EXPECT_EQ(adapted[1].amplitude, 0.0);
}

TEST(CueAdaptation, StrengthBecomesPulseWidthForOnOffActuators) {
    // Half strength for 0.4 s: ten 40 ms periods, each on for 20 ms.
    const auto adapted =
        adapt_cues({drive(0.0, 0.5), position(0.0, 0), drive(0.4, 0.0)}, 1.0, {.amplitude = false});
    const auto on_off = drives(adapted);
    ASSERT_EQ(on_off.size(), 20u);
    for (std::size_t n = 0; n < 10; ++n) {
        EXPECT_NEAR(on_off[2 * n].at, 0.04 * static_cast<double>(n), 1e-12);
        EXPECT_EQ(on_off[2 * n].amplitude, 1.0);
        EXPECT_NEAR(on_off[2 * n + 1].at, 0.04 * static_cast<double>(n) + 0.02, 1e-12);
        EXPECT_EQ(on_off[2 * n + 1].amplitude, 0.0);
    }
    EXPECT_NEAR(on_time(on_off, 1.0), 0.2, 1e-9);
    EXPECT_EQ(adapted[1].kind, Cue::Kind::position);  // positions stay, after the drive
}

TEST(CueAdaptation, PulseWidthFollowsTheScaledStrength) {
    const std::vector<Cue> cues = {drive(0.0, 1.0), drive(0.4, 0.0)};
    const auto full = drives(adapt_cues(cues, 1.0, {.amplitude = false}));
    ASSERT_EQ(full.size(), 2u);  // full strength is simply on
    EXPECT_EQ(full[0].amplitude, 1.0);
    EXPECT_EQ(full[1].at, 0.4);
    const auto quarter = drives(adapt_cues(cues, 1.0, {.amplitude = false, .scale = 0.25}));
    EXPECT_NEAR(on_time(quarter, 1.0), 0.1, 1e-9);
    // Too weak to spin a motor up within one pulse: nothing at all.
    const auto faint = drives(adapt_cues(cues, 1.0, {.amplitude = false, .scale = 0.05}));
    EXPECT_NEAR(on_time(faint, 1.0), 0.0, 1e-12);
}

TEST(CueAdaptation, ALastPulseIsCutAtTheEndOfItsNote) {
    const auto on_off =
        drives(adapt_cues({drive(0.0, 0.75), drive(0.05, 0.0)}, 1.0, {.amplitude = false}));
    // Periods at 0 (30 ms on) and 40 ms (cut at 50 ms).
    ASSERT_EQ(on_off.size(), 4u);
    EXPECT_NEAR(on_off[2].at, 0.04, 1e-12);
    EXPECT_NEAR(on_off[3].at, 0.05, 1e-12);
    EXPECT_EQ(on_off[3].amplitude, 0.0);
}

TEST(CueAdaptation, ACrescendoBecomesOneEnvelope) {
    const Performance performance(bundle_from(
        one_clef_score("<Bar clef=\"c\"><Note length=\"quarter\" number=\"2\" string=\"1\" "
                       "dynamics=\"crescendo\"/></Bar>"),
        {{"c.xml", sine_clef(1.0, {150}, {0.5, 1.0})}}));
    const auto steps = drives(cue_schedule(performance));
    ASSERT_GE(steps.size(), 200u);
    const auto adapted =
        drives(adapt_cues(cue_schedule(performance), performance.duration(), {.envelopes = true}));
    ASSERT_LE(adapted.size(), 4u) << "the steps were not merged";
    const auto ramp = std::find_if(adapted.begin(), adapted.end(),
                                   [](const Cue& cue) { return cue.ramp_s > 0.0; });
    ASSERT_NE(ramp, adapted.end());
    EXPECT_LT(ramp->amplitude, ramp->ramp_to);  // rising
    EXPECT_NEAR(ramp->ramp_to, steps[steps.size() - 2].amplitude, 1e-9);
    EXPECT_NEAR(ramp->at + ramp->ramp_s, steps[steps.size() - 2].at, 1e-9);
    EXPECT_EQ(adapted.back().amplitude, 0.0);
    EXPECT_EQ(adapted.back().at, steps.back().at);
}

TEST(CueAdaptation, CurvesAndGlidesStayInSteps) {
    // Not on one line: a rise then a fall, and a glide that changes the frequency.
    const std::vector<Cue> bend = {drive(0.0, 0.2), drive(0.005, 0.4), drive(0.010, 0.3),
                                   drive(0.015, 0.1), drive(0.020, 0.0)};
    EXPECT_EQ(drives(adapt_cues(bend, 1.0, {.envelopes = true})).size(), bend.size());
    const std::vector<Cue> glide = {drive(0.0, 0.5, 100.0), drive(0.005, 0.5, 110.0),
                                    drive(0.010, 0.5, 120.0), drive(0.015, 0.0)};
    const auto adapted = drives(adapt_cues(glide, 1.0, {.envelopes = true}));
    EXPECT_EQ(adapted.size(), glide.size());
    EXPECT_TRUE(std::none_of(adapted.begin(), adapted.end(),
                             [](const Cue& cue) { return cue.ramp_s > 0.0; }));
}

TEST(CueAdaptation, DistantStepsOnOneLineAreNotARamp) {
    // Three notes whose strengths happen to be collinear are separate notes, not a ramp.
    const std::vector<Cue> notes = {drive(0.0, 0.2), drive(0.5, 0.4), drive(1.0, 0.6),
                                    drive(1.5, 0.0)};
    const auto adapted = drives(adapt_cues(notes, 2.0, {.envelopes = true}));
    EXPECT_EQ(adapted.size(), notes.size());
}

}  // namespace
}  // namespace vibscore::render
