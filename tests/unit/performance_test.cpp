#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "daemon/render/performance.hpp"
#include "daemon/render/sampler.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

using testing::bundle_from;
using testing::one_clef_score;
using testing::sine_clef;

constexpr double kTwoPi = 2.0 * M_PI;

Performance perform(const std::string& bars, const std::string& clef,
                    const RenderOptions& options = {}) {
    return Performance(bundle_from(one_clef_score(bars), {{"c.xml", clef}}), options);
}

std::string note(const char* length, int number, int string, const std::string& extra = "") {
    return std::string("<Note length=\"") + length + "\" number=\"" + std::to_string(number) +
           "\" string=\"" + std::to_string(string) + "\" " + extra + "/>";
}

std::string bar(const std::string& symbols) {
    return "<Bar clef=\"c\">" + symbols + "</Bar>";
}

// Thesis Fig. 2.3c: with a sine clef at tempo 1 s, an 8th (150 Hz, A=1) tied by legato to a
// quarter (200 Hz, A=2), an 8th rest and a half note (100 Hz, A=2).
double figure_2_3c(double t) {
    if (t < 0.0)
        return 0.0;
    if (t < 0.5)
        return 1.0 * std::sin(kTwoPi * 150 * t);
    if (t < 1.5)
        return 2.0 * std::sin(kTwoPi * 200 * t);
    if (t < 2.0)
        return 0.0;
    if (t < 4.0)
        return 2.0 * std::sin(kTwoPi * 100 * t);
    return 0.0;
}

Performance figure_2_3_first_measure() {
    return perform(bar(note("8th", 1, 2, "legato=\"1\"") + note("quarter", 2, 3, "legato=\"1\"") +
                       "<Rest length=\"8th\"/>" + note("half", 2, 1)),
                   sine_clef(1.0, {100, 150, 200}, {1.0, 2.0}));
}

TEST(Golden, Figure23cEquationToOneNanoUnit) {
    const auto performance = figure_2_3_first_measure();
    EXPECT_DOUBLE_EQ(performance.duration(), 4.0);
    double worst = 0.0;
    for (int k = -10; k <= 44'000; ++k) {
        const double t = k / 11'000.0 + 1e-7;
        worst = std::max(worst, std::abs(performance.value_at(t) - figure_2_3c(t)));
    }
    EXPECT_LT(worst, 1e-9);
}

TEST(Golden, Figure23cSampledAt8kHz) {
    const auto performance = figure_2_3_first_measure();
    std::vector<double> samples(4 * 8000 + 100);
    render_signal(performance, 8000.0, 0, samples);
    double worst = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        worst = std::max(worst, std::abs(samples[k] - figure_2_3c(k / 8000.0)));
    }
    EXPECT_LT(worst, 1e-9);
}

TEST(Timing, EachLengthLastsItsBeatsTimesTheTempo) {
    const auto performance = perform(bar(note("whole", 1, 1) + "<Rest length=\"half_dot\"/>" +
                                         note("16th_dot", 1, 1) + note("32th", 1, 1)),
                                     sine_clef(0.15, {100}, {1}));
    const auto& timeline = performance.timeline();
    ASSERT_EQ(timeline.size(), 4u);
    EXPECT_DOUBLE_EQ(timeline[1].onset, 0.6);
    EXPECT_DOUBLE_EQ(timeline[1].length, 0.45);
    EXPECT_DOUBLE_EQ(timeline[2].onset, 1.05);
    EXPECT_DOUBLE_EQ(timeline[3].onset, 1.05 + 0.375 * 0.15);
    EXPECT_DOUBLE_EQ(performance.duration(), 1.05 + 0.5 * 0.15);
}

TEST(Timing, BlankTakesNoTime) {
    const auto performance =
        perform(bar(note("quarter", 1, 1) + "<Blank/><Blank/>" + note("quarter", 1, 1)),
                sine_clef(1.0, {100}, {1}));
    ASSERT_EQ(performance.tones().size(), 2u);
    EXPECT_DOUBLE_EQ(performance.tones()[1].onset, 1.0);
    // ... and does not separate the notes either: the first still gets its silence.
    EXPECT_DOUBLE_EQ(performance.tones()[0].duration, 0.97);
}

TEST(Timing, EachBarUsesItsOwnClefsTempoAndPitch) {
    const std::string score =
        "<VibScore><Clef id=\"slow\" href=\"slow.xml\"/><Clef id=\"fast\" href=\"fast.xml\"/>"
        "<Bar clef=\"slow\">" +
        note("quarter", 1, 1) + "</Bar><Bar clef=\"fast\">" + note("quarter", 1, 1) +
        "</Bar></VibScore>";
    const Performance performance(bundle_from(score, {{"slow.xml", sine_clef(1.0, {100}, {1})},
                                                      {"fast.xml", sine_clef(0.25, {250}, {3})}}));
    const auto& second = performance.tones().at(1);
    EXPECT_DOUBLE_EQ(second.onset, 1.0);
    EXPECT_DOUBLE_EQ(second.duration, 0.25);
    EXPECT_EQ(second.frequency_start, 250.0);
    EXPECT_EQ(second.amplitude_start, 3.0);
    EXPECT_NEAR(performance.value_at(1.0 + 1.0 / 1000.0), 3.0, 1e-12);  // quarter cycle of 250 Hz
    EXPECT_DOUBLE_EQ(performance.duration(), 1.25);
}

TEST(Silence, SeparatesAdjacentNotesByCuttingTheEarlierOnesEnd) {
    const auto performance =
        perform(bar(note("quarter", 1, 1) + note("quarter", 1, 1)), sine_clef(1.0, {100}, {1}));
    const auto& tones = performance.tones();
    EXPECT_DOUBLE_EQ(tones[0].duration, 0.97);
    EXPECT_DOUBLE_EQ(tones[1].onset, 1.0);     // onsets stay on the beat
    EXPECT_DOUBLE_EQ(tones[1].duration, 1.0);  // the last note keeps its length
    EXPECT_EQ(performance.value_at(0.975), 0.0);
    EXPECT_NE(performance.value_at(0.9625), 0.0);
}

TEST(Silence, IsAtMostAQuarterOfAShortNote) {
    const auto performance =
        perform(bar(note("32th", 1, 1) + note("32th", 1, 1)), sine_clef(0.15, {100}, {1}));
    EXPECT_DOUBLE_EQ(performance.tones()[0].duration, 0.75 * 0.125 * 0.15);
}

TEST(Silence, IsNotAddedBeforeARestOrAcrossLegato) {
    const auto before_rest =
        perform(bar(note("quarter", 1, 1) + "<Rest length=\"8th\"/>"), sine_clef(1.0, {100}, {1}));
    EXPECT_DOUBLE_EQ(before_rest.tones()[0].duration, 1.0);
    const auto tied = perform(bar(note("quarter", 1, 1, "legato=\"3\"") +
                                  note("quarter", 1, 1, "legato=\"3\"") + note("quarter", 1, 1)),
                              sine_clef(1.0, {100}, {1}));
    EXPECT_DOUBLE_EQ(tied.tones()[0].duration, 1.0);
    EXPECT_DOUBLE_EQ(tied.tones()[1].duration, 0.97);  // not tied to the third note
}

TEST(Silence, DifferentLegatoSerialsDoNotTie) {
    const auto performance =
        perform(bar(note("quarter", 1, 1, "legato=\"1\"") + note("quarter", 1, 1, "legato=\"2\"")),
                sine_clef(1.0, {100}, {1}));
    EXPECT_DOUBLE_EQ(performance.tones()[0].duration, 0.97);
}

TEST(Silence, SeparatesNotesAcrossABarLine) {
    const auto performance = perform(bar(note("quarter", 1, 1)) + bar(note("quarter", 1, 1)),
                                     sine_clef(1.0, {100}, {1}));
    EXPECT_DOUBLE_EQ(performance.tones()[0].duration, 0.97);
}

TEST(Silence, LengthIsAnOption) {
    RenderOptions options;
    options.separation_s = 0.05;
    const auto performance = perform(bar(note("quarter", 1, 1) + note("quarter", 1, 1)),
                                     sine_clef(1.0, {100}, {1}), options);
    EXPECT_DOUBLE_EQ(performance.tones()[0].duration, 0.95);
}

TEST(Phase, AnUntiedNoteStartsAtZeroPhase) {
    const auto performance =
        perform(bar(note("quarter", 1, 1) + note("quarter", 1, 1)), sine_clef(1.0, {130}, {1}));
    EXPECT_NEAR(performance.value_at(1.0), 0.0, 1e-12);
    EXPECT_NEAR(performance.value_at(1.0 + 0.25 / 130), 1.0, 1e-12);
}

TEST(Phase, LegatoContinuesThePhaseSoTheSignalHasNoStep) {
    const auto performance =
        perform(bar(note("quarter", 1, 1, "legato=\"1\"") + note("quarter", 2, 2, "legato=\"1\"")),
                sine_clef(0.0123, {130, 170}, {1, 1}));
    const double boundary = 0.0123;
    const double before = performance.value_at(boundary - 1e-9);
    const double after = performance.value_at(boundary);
    EXPECT_NEAR(before, after, 1e-5);
    EXPECT_NE(after, 0.0);
}

TEST(Portamento, GlidesPitchGeometricallyAndStrengthLinearly) {
    const auto performance = perform(
        bar(note("quarter", 1, 1, "portamento=\"4\"") + note("quarter", 3, 3, "portamento=\"4\"")),
        sine_clef(1.0, {100, 150, 400}, {1, 2, 3}));
    const auto& first = performance.tones()[0];
    EXPECT_DOUBLE_EQ(first.duration, 1.0);  // no silence
    EXPECT_EQ(first.frequency_start, 100.0);
    EXPECT_EQ(first.frequency_end, 400.0);
    EXPECT_EQ(first.amplitude_start, 1.0);
    EXPECT_EQ(first.amplitude_end, 3.0);
    EXPECT_DOUBLE_EQ(Performance::amplitude(first, 0.5), 2.0);
    // Instantaneous frequency half-way is the geometric mean: 200 Hz.
    const double h = 1e-6;
    const double frequency =
        (Performance::sine_cycles(first, 0.5 + h) - Performance::sine_cycles(first, 0.5 - h)) /
        (2 * h);
    EXPECT_NEAR(frequency, 200.0, 1e-3);
    // The second note holds its own pitch and strength, starting where the glide ended.
    const auto& second = performance.tones()[1];
    EXPECT_EQ(second.frequency_start, 400.0);
    EXPECT_EQ(second.frequency_end, 400.0);
    EXPECT_NEAR(performance.value_at(1.0 - 1e-9), performance.value_at(1.0), 1e-4);
}

TEST(Portamento, CrossFadesTheWaveformsOfShapeClefs) {
    const std::string clef =
        "<VibClef type=\"line\"><Tempo>1</Tempo><Number>1</Number><Strings>"
        "<String><Point time=\"0\" level=\"0.2\"/><Point time=\"1\" level=\"0.2\"/></String>"
        "<String><Point time=\"0\" level=\"1\"/><Point time=\"1\" level=\"1\"/></String>"
        "</Strings></VibClef>";
    const auto performance = perform(
        bar(note("quarter", 1, 1, "portamento=\"1\"") + note("quarter", 1, 2, "portamento=\"1\"")),
        clef);
    EXPECT_NEAR(performance.value_at(0.0), 0.2, 1e-12);
    EXPECT_NEAR(performance.value_at(0.5), 0.6, 1e-12);
    EXPECT_NEAR(performance.value_at(1.5), 1.0, 1e-12);
}

TEST(Portamento, BetweenSineAndShapeClefsTiesWithoutGlidingPitch) {
    const std::string score =
        "<VibScore><Clef id=\"s\" href=\"s.xml\"/><Clef id=\"l\" href=\"l.xml\"/><Bar clef=\"s\">" +
        note("quarter", 1, 1, "portamento=\"1\"") + "</Bar><Bar clef=\"l\">" +
        note("quarter", 1, 1, "portamento=\"1\"") + "</Bar></VibScore>";
    const std::string line =
        "<VibClef type=\"line\"><Tempo>1</Tempo><Number>0.5</Number><Strings><String>"
        "<Point time=\"0\" level=\"1\"/></String></Strings></VibClef>";
    const Performance performance(
        bundle_from(score, {{"s.xml", sine_clef(1, {100}, {1})}, {"l.xml", line}}));
    const auto& first = performance.tones()[0];
    EXPECT_DOUBLE_EQ(first.duration, 1.0);
    EXPECT_EQ(first.frequency_end, 100.0);
    EXPECT_EQ(first.amplitude_end, 0.5);
}

TEST(Dynamics, ALoneCrescendoRisesFromSilenceToItsStrength) {
    const auto performance =
        perform(bar(note("half", 2, 1, "dynamics=\"crescendo\"")), sine_clef(1.0, {100}, {1, 4}));
    const auto& tone = performance.tones()[0];
    EXPECT_EQ(tone.amplitude_start, 0.0);
    EXPECT_EQ(tone.amplitude_end, 4.0);
    EXPECT_DOUBLE_EQ(performance.envelope_at(1.0), 2.0);
}

TEST(Dynamics, ALoneDecrescendoFallsFromItsStrengthToSilence) {
    const auto performance =
        perform(bar(note("half", 2, 1, "dynamics=\"decrescendo\"")), sine_clef(1.0, {100}, {1, 4}));
    EXPECT_EQ(performance.tones()[0].amplitude_start, 4.0);
    EXPECT_EQ(performance.tones()[0].amplitude_end, 0.0);
}

TEST(Dynamics, ACrescendoRunIsOneHairpinThroughTheNotesStrengths) {
    const std::string c = "dynamics=\"crescendo\"";
    const auto performance = perform(bar(note("8th", 1, 1, c) + note("8th", 2, 1, c) + "<Blank/>" +
                                         note("8th", 3, 1, c) + note("8th", 3, 1)),
                                     sine_clef(1.0, {100}, {1, 2, 3}));
    const auto& tones = performance.tones();
    EXPECT_EQ(tones[0].amplitude_start, 0.0);
    EXPECT_EQ(tones[0].amplitude_end, 1.0);
    EXPECT_EQ(tones[1].amplitude_start, 1.0);
    EXPECT_EQ(tones[1].amplitude_end, 2.0);
    EXPECT_EQ(tones[2].amplitude_start, 2.0);
    EXPECT_EQ(tones[2].amplitude_end, 3.0);
    EXPECT_EQ(tones[3].amplitude_start, 3.0);  // after the hairpin: steady
}

TEST(Dynamics, ADecrescendoRunFallsThroughTheNotesToSilence) {
    const std::string d = "dynamics=\"decrescendo\"";
    const auto performance =
        perform(bar(note("8th", 3, 1, d) + note("8th", 2, 1, d) + note("8th", 1, 1, d)),
                sine_clef(1.0, {100}, {1, 2, 3}));
    const auto& tones = performance.tones();
    EXPECT_EQ(tones[0].amplitude_start, 3.0);
    EXPECT_EQ(tones[0].amplitude_end, 2.0);
    EXPECT_EQ(tones[1].amplitude_end, 1.0);
    EXPECT_EQ(tones[2].amplitude_end, 0.0);
}

TEST(Dynamics, ARestEndsTheHairpin) {
    const std::string c = "dynamics=\"crescendo\"";
    const auto performance =
        perform(bar(note("8th", 2, 1, c) + "<Rest length=\"8th\"/>" + note("8th", 3, 1, c)),
                sine_clef(1.0, {100}, {1, 2, 3}));
    EXPECT_EQ(performance.tones()[1].amplitude_start, 0.0);
}

const std::string kRampClef =
    "<VibClef type=\"line\"><Tempo>1</Tempo><Numbers><Number>1</Number><Number>2</Number>"
    "</Numbers><Strings><String><Point time=\"0\" level=\"0\"/><Point time=\"1\" level=\"1\"/>"
    "</String></Strings></VibClef>";

TEST(Shapes, AnEighthPlaysTheFirstHalfOfTheQuarterWaveform) {
    const auto performance = perform(bar(note("8th", 1, 1)), kRampClef);
    EXPECT_NEAR(performance.value_at(0.25), 0.25, 1e-12);
    EXPECT_NEAR(performance.value_at(0.4999), 0.4999, 1e-12);
    EXPECT_EQ(performance.value_at(0.5), 0.0);
}

TEST(Shapes, AHalfNotePlaysTheQuarterWaveformTwiceScaledByItsNumber) {
    const auto performance = perform(bar(note("half", 2, 1)), kRampClef);
    EXPECT_NEAR(performance.value_at(0.25), 0.5, 1e-12);
    EXPECT_NEAR(performance.value_at(1.25), 0.5, 1e-12);
    EXPECT_NEAR(performance.value_at(1.75), 1.5, 1e-12);
}

TEST(Shapes, EnvelopeOfAShapeIsItsMagnitude) {
    const auto performance = perform(bar(note("half", 2, 1)), kRampClef);
    EXPECT_NEAR(performance.envelope_at(1.75), 1.5, 1e-12);
    EXPECT_NEAR(performance.peak_amplitude(), 2.0, 1e-12);
}

TEST(Waveform, LineJoinsPointsWithStraightSegmentsAndHoldsAtTheEnds) {
    const Waveform line(ClefType::line, {{0.2, 0.4}, {0.6, 0.8}, {0.8, 0.6}});
    EXPECT_DOUBLE_EQ(line.level(0.0), 0.4);
    EXPECT_DOUBLE_EQ(line.level(0.4), 0.6);
    EXPECT_DOUBLE_EQ(line.level(0.7), 0.7);
    EXPECT_DOUBLE_EQ(line.level(1.0), 0.6);
}

TEST(Waveform, EqualTimesMakeAStep) {
    const Waveform square(ClefType::line, {{0, 1}, {0.5, 1}, {0.5, 0}, {1, 0}});
    EXPECT_DOUBLE_EQ(square.level(0.4999), 1.0);
    EXPECT_DOUBLE_EQ(square.level(0.5), 0.0);
    EXPECT_DOUBLE_EQ(square.level(0.75), 0.0);
    const Waveform curve_square(ClefType::curve, {{0, 1}, {0.5, 1}, {0.5, 0}, {1, 0}});
    EXPECT_DOUBLE_EQ(curve_square.level(0.25), 1.0);
    EXPECT_DOUBLE_EQ(curve_square.level(0.75), 0.0);
}

TEST(Waveform, CurvePassesThroughItsPointsWithCatmullRomTangents) {
    const Waveform bump(ClefType::curve, {{0, 0}, {0.5, 1}, {1, 0}});
    EXPECT_DOUBLE_EQ(bump.level(0.0), 0.0);
    EXPECT_DOUBLE_EQ(bump.level(0.5), 1.0);
    EXPECT_DOUBLE_EQ(bump.level(1.0), 0.0);
    // Hermite segment with end tangents 2 and 0 (per unit time), evaluated half-way.
    EXPECT_DOUBLE_EQ(bump.level(0.25), 0.625);
    EXPECT_DOUBLE_EQ(bump.level(0.75), 0.625);
    // Collinear points give a straight line.
    const Waveform straight(ClefType::curve, {{0, 0}, {0.25, 0.25}, {0.75, 0.75}, {1, 1}});
    EXPECT_NEAR(straight.level(0.6), 0.6, 1e-15);
}

TEST(Waveform, ASinglePointIsAConstant) {
    const Waveform flat(ClefType::curve, {{0.3, 0.7}});
    EXPECT_EQ(flat.level(0.0), 0.7);
    EXPECT_EQ(flat.level(0.99), 0.7);
}

TEST(Options, StartBarSkipsEarlierBarsAndStartsTimeThere) {
    RenderOptions options;
    options.start_bar = 1;
    const auto performance = perform(bar(note("whole", 1, 1)) + bar(note("quarter", 1, 1)),
                                     sine_clef(1.0, {100}, {1}), options);
    ASSERT_EQ(performance.tones().size(), 1u);
    EXPECT_EQ(performance.tones()[0].bar, 1u);
    EXPECT_EQ(performance.tones()[0].onset, 0.0);
    EXPECT_DOUBLE_EQ(performance.duration(), 1.0);
}

}  // namespace
}  // namespace vibscore::render
