// Compensation (daemon/render/drive_planner.*, the ActuatorDrives stage of cue_adaptation): each
// rule against the actuator model's closed forms, and each limit at its edge.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "daemon/actuator/physics.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/drive_planner.hpp"
#include "daemon/render/performance.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

using actuator::Brake;
using actuator::Declaration;
using actuator::Kind;
using actuator::Physics;

constexpr double kRated = 0.7;
constexpr double kFull = 1.0 / kRated;  // strength at full scale
constexpr double kUp = 0.040, kDown = 0.080;

Declaration erm(Brake brake = Brake::reverse) {
    Declaration d;
    d.kind = Kind::erm;
    d.rated_drive = kRated;
    d.spin_up_s = kUp;
    d.spin_down_s = kDown;
    d.brake = brake;
    return d;
}

Declaration lra(Brake brake = Brake::reverse) {
    Declaration d;
    d.kind = Kind::lra;
    d.rated_drive = kRated;
    d.resonance_hz = 175.0;
    d.q = 15.0;
    d.brake = brake;
    return d;
}

const double kTau = actuator::lra_time_constant_s(175.0, 15.0);

std::vector<Cue> plan(DrivePlanner& planner, double at, double until, double strength,
                      double frequency = 0.0, bool silence_follows = false) {
    std::vector<Cue> out;
    planner.segment(at, until, strength, frequency, silence_follows, out);
    return out;
}

MATCHER_P3(DriveIs, at, amplitude, tolerance, "") {
    return std::abs(arg.at - at) <= tolerance && std::abs(arg.amplitude - amplitude) <= 1e-12;
}

// The strength the actuator reaches at `t` under `drives`.
double strength_at(const Declaration& d, const std::vector<Cue>& drives, double t) {
    const auto samples = produced_strength(d, drives, 1e6, static_cast<std::size_t>(t * 1e6) + 1);
    return samples.back();
}

TEST(DrivePlanner, StrengthOneIsTheRatedDrive) {
    DrivePlanner planner(erm(), {.compensation = false});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 1.0), ::testing::ElementsAre(DriveIs(0.0, kRated, 0.0)));
    EXPECT_THAT(plan(planner, 1.0, 2.0, 0.5), ::testing::ElementsAre(DriveIs(1.0, 0.35, 0.0)));
    // Compensation off still never exceeds full scale.
    EXPECT_THAT(plan(planner, 2.0, 3.0, 2.0), ::testing::ElementsAre(DriveIs(2.0, 1.0, 0.0)));
}

TEST(DrivePlanner, AnOnsetIsOverdrivenExactlyAsLongAsTheModelTakesThenHeld) {
    DrivePlanner planner(erm(), {});
    const auto drives = plan(planner, 0.0, 1.0, 1.0);
    const double overdrive = kUp * std::log(kFull / (kFull - 1.0));
    ASSERT_THAT(drives,
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0), DriveIs(overdrive, kRated, 1e-12)));
    EXPECT_NEAR(strength_at(erm(), drives, overdrive), 1.0, 1e-5);
    EXPECT_NEAR(Physics::strength(planner.carry().state), 1.0, 1e-9);
}

TEST(DrivePlanner, OverdriveStartsFromWhereTheActuatorIsMidDecay) {
    DrivePlanner planner(erm(Brake::none), {});
    plan(planner, 0.0, 1.0, 1.0);
    plan(planner, 1.0, 1.02, 0.0);  // coasts 20 ms: down to e^(-1/4)
    const double left = std::exp(-0.020 / kDown);
    const auto drives = plan(planner, 1.02, 2.0, 1.0);
    const double overdrive = kUp * std::log((kFull - left) / (kFull - 1.0));
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.02, 1.0, 0.0),
                                               DriveIs(1.02 + overdrive, kRated, 1e-9)));
}

TEST(DrivePlanner, OverdriveNeverOutlastsItsNoteNorTheModelsNeed) {
    // A note shorter than the overdrive it would need: full scale throughout, and no more.
    DrivePlanner planner(erm(), {});
    const double needed = kUp * std::log(kFull / (kFull - 1.0));
    EXPECT_THAT(plan(planner, 0.0, needed * 0.5, 1.0),
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
    // The edge: an overdrive just above the shortest one backends resolve is kept ...
    const double min_pulse = PlannerOptions{}.min_pulse_s;
    const double just_above = kFull - (kFull - 0.5) * std::exp(-(min_pulse * 1.01) / kUp);
    DrivePlanner above(erm(), {});
    plan(above, 0.0, 1.0, 0.5);
    EXPECT_THAT(plan(above, 1.0, 2.0, just_above),
                ::testing::ElementsAre(DriveIs(1.0, 1.0, 0.0),
                                       DriveIs(1.0 + min_pulse * 1.01, just_above * kRated, 1e-9)));
    // ... one just below it goes straight to the hold.
    const double just_below = kFull - (kFull - 0.5) * std::exp(-(min_pulse * 0.99) / kUp);
    DrivePlanner below(erm(), {});
    plan(below, 0.0, 1.0, 0.5);
    EXPECT_THAT(plan(below, 1.0, 2.0, just_below),
                ::testing::ElementsAre(DriveIs(1.0, just_below * kRated, 0.0)));
}

TEST(DrivePlanner, NeverAboveFullScaleAndWhatIsOutOfReachIsDrivenFull) {
    DrivePlanner planner(erm(), {});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 2.0), ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
    // The last strength full scale holds is reached, and held at full scale.
    DrivePlanner edge(erm(), {});
    const auto drives = plan(edge, 0.0, 1.0, kFull);
    for (const auto& cue : drives) {
        EXPECT_LE(std::abs(cue.amplitude), 1.0);
    }
}

TEST(DrivePlanner, AnEndIsBrakedBackwardsForExactlyAsLongAsItTakesToStop) {
    DrivePlanner planner(erm(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, INFINITY, 0.0);
    const double brake = kUp * std::log((1.0 + kFull) / kFull);
    EXPECT_THAT(drives,
                ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0), DriveIs(1.0 + brake, 0.0, 1e-9)));
}

TEST(DrivePlanner, AFallIsBrakedToTheWrittenLevelThenHeld) {
    DrivePlanner planner(erm(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, 2.0, 0.5);
    const double brake = kUp * std::log((1.0 + kFull) / (0.5 + kFull));
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0),
                                               DriveIs(1.0 + brake, 0.5 * kRated, 1e-9)));
}

TEST(DrivePlanner, WithoutReverseAFallCoastsToTheWrittenLevel) {
    DrivePlanner planner(erm(Brake::none), {.reverse = false});
    plan(planner, 0.0, 1.0, 1.0);
    const auto drives = plan(planner, 1.0, 2.0, 0.5);
    EXPECT_THAT(drives, ::testing::ElementsAre(DriveIs(1.0, 0.0, 0.0),
                                               DriveIs(1.0 + kDown * std::log(2.0), 0.35, 1e-9)));
}

TEST(DrivePlanner, WithoutReverseANoteEndsEarlySoItsFeltEndIsOnTime) {
    DrivePlanner planner(erm(Brake::none), {.reverse = false});
    const auto drives = plan(planner, 0.0, 1.0, 1.0, 0.0, true);
    // Long enough to settle: the drive stops spin-down x ln 2 early, so the strength is half the
    // written one exactly at the written end.
    ASSERT_EQ(drives.size(), 3u);
    EXPECT_NEAR(drives[2].at, 1.0 - kDown * std::log(2.0), 1e-9);
    EXPECT_EQ(drives[2].amplitude, 0.0);
    EXPECT_NEAR(strength_at(erm(Brake::none), drives, 1.0), 0.5, 1e-5);
    EXPECT_NEAR(Physics::strength(planner.carry().state), 0.5, 1e-9);
}

TEST(DrivePlanner, ANoteTooShortToLingerKeepsAllItsDrive) {
    DrivePlanner planner(erm(Brake::none), {.reverse = false});
    // 5 ms at full scale from rest: strength 0.16 at the end, below half of 1.
    EXPECT_THAT(plan(planner, 0.0, 0.005, 1.0, 0.0, true),
                ::testing::ElementsAre(DriveIs(0.0, 1.0, 0.0)));
}

TEST(DrivePlanner, WithReverseANoteKeepsItsDriveToTheWrittenEnd) {
    DrivePlanner planner(erm(), {.reverse = true});
    const auto drives = plan(planner, 0.0, 1.0, 1.0, 0.0, true);
    EXPECT_EQ(drives.size(), 2u);
    EXPECT_EQ(drives.back().amplitude, kRated);
}

TEST(DrivePlanner, AnLraIsDrivenHarderAwayFromItsResonance) {
    DrivePlanner planner(lra(), {});
    plan(planner, 0.0, 1.0, 0.5, 181.0);
    const double gain = Physics::lra_gain(181.0, 175.0, 15.0);
    EXPECT_NEAR(planner.carry().drive.amplitude, 0.5 * kRated / gain, 1e-12);
    EXPECT_EQ(planner.carry().drive.frequency_hz, 181.0);
    EXPECT_NEAR(Physics::strength(planner.carry().state), 0.5, 0.01);
    // Beyond what full scale gives there: full scale, and the strength stays short.
    DrivePlanner far(lra(), {});
    plan(far, 0.0, 1.0, 0.5, 235.0);
    EXPECT_EQ(far.carry().drive.amplitude, 1.0);
}

TEST(DrivePlanner, AnLraIsBrakedInAntiPhaseAtItsOwnFrequency) {
    DrivePlanner planner(lra(), {.reverse = true});
    plan(planner, 0.0, 1.0, 1.0, 175.0);
    const auto drives = plan(planner, 1.0, INFINITY, 0.0, 0.0);
    const double brake = kTau * std::log((1.0 + kFull) / kFull);
    ASSERT_THAT(drives,
                ::testing::ElementsAre(DriveIs(1.0, -1.0, 0.0), DriveIs(1.0 + brake, 0.0, 1e-6)));
    EXPECT_EQ(drives[0].frequency_hz, 175.0);
}

TEST(DrivePlanner, TheScaleIsThePlaybacksIntensity) {
    DrivePlanner planner(erm(), {.scale = 0.5, .compensation = false});
    EXPECT_THAT(plan(planner, 0.0, 1.0, 1.0), ::testing::ElementsAre(DriveIs(0.0, 0.35, 0.0)));
}

// Whatever the envelope, on either kind, with or without reverse: every drive within full scale,
// in time order, backwards only with reverse, and no overdrive or brake carrying the actuator
// past the written strength (it ends where the model gets there, or at the segment's end).
TEST(DrivePlanner, KeepsItsLimitsOverAnyEnvelope) {
    std::mt19937 random(22);
    std::uniform_real_distribution<double> strength(0.0, 1.6), length(0.001, 0.15),
        frequency(150.0, 200.0);
    for (const Declaration& declared :
         {erm(Brake::reverse), erm(Brake::none), lra(Brake::reverse), lra(Brake::none)}) {
        const bool reverse = declared.brake == Brake::reverse;
        DrivePlanner planner(declared, {.reverse = reverse});
        const Physics physics(declared);
        double at = 0.0;
        double previous = 0.0;
        for (int i = 0; i < 400; ++i) {
            const double written = i % 3 == 0 ? 0.0 : strength(random);
            const double until = at + length(random);
            const double f = declared.kind == Kind::lra ? frequency(random) : 0.0;
            const auto before = planner.carry().state;
            const auto drives = plan(planner, at, until, written, f, i % 3 == 2);
            for (std::size_t k = 0; k < drives.size(); ++k) {
                const Cue& cue = drives[k];
                ASSERT_LE(std::abs(cue.amplitude), 1.0);
                ASSERT_TRUE(reverse || cue.amplitude >= 0.0);
                ASSERT_GE(cue.at, previous);
                ASSERT_LT(cue.at, until);
                previous = cue.at;
            }
            // A push (full scale either way) that the planner ends within the segment for the
            // hold has brought the strength to the written one, not beyond. (A drive that stops
            // instead ends a note early: the felt end.)
            const double hold = std::min(1.0, physics.amplitude_for(written, f));
            if (drives.size() == 2 && std::abs(drives[0].amplitude) == 1.0 && drives[0].at == at &&
                std::abs(drives[1].amplitude - hold) < 1e-12) {
                const auto state = physics.advance(
                    before, {drives[0].amplitude, drives[0].frequency_hz}, drives[1].at - at);
                const double reached = Physics::strength(state);
                const double target = std::min(written, physics.steady_strength({1.0, f}));
                if (declared.kind == Kind::erm) {
                    EXPECT_NEAR(reached, written, 1e-6) << "segment " << i;
                } else if (written > 0.0 && drives[0].amplitude > 0.0) {
                    EXPECT_LE(reached, std::max(target, written) + 1e-6) << "segment " << i;
                } else if (written > 0.0) {
                    // A brake stops where it stops helping: never below the written strength.
                    EXPECT_GE(reached, written - 1e-6) << "segment " << i;
                } else {
                    // To rest: exactly, or (no brake frequency nulls it) as low as it gets.
                    EXPECT_LT(reached, Physics::strength(before)) << "segment " << i;
                }
            }
            at = until;
        }
    }
}

// The stage in the pipeline: what the player receives for a score.
CueAdaptation declared(const Declaration& d, bool reverse = true) {
    CueAdaptation adaptation;
    adaptation.actuator = d;
    adaptation.reverse = reverse;
    return adaptation;
}

Cue drive(double at, double amplitude, double frequency_hz = 0.0) {
    return drive_at(at, amplitude, frequency_hz);
}

Cue position(double at, std::size_t symbol) {
    Cue cue;
    cue.at = at;
    cue.kind = Cue::Kind::position;
    cue.symbol = symbol;
    return cue;
}

// A one-bar score on a sine clef (tempo 0.2 s; strings 170-180 Hz, inside the LRA's band;
// numbers 0.5 and 1) as the declared actuator produces it with compensation, sampled at 1 kHz.
struct Felt {
    std::vector<double> written, produced;
};
Felt felt(const std::string& notes, const Declaration& declared) {
    const auto bundle = testing::bundle_from(
        testing::one_clef_score("<Bar clef=\"c\">" + notes + "</Bar>"),
        {{"c.xml", testing::sine_clef(0.2, {170.0, 175.0, 180.0}, {0.5, 1.0})}});
    const Performance performance(bundle);
    ResponseOptions options;
    options.tail_s = 0.1;
    const auto response = actuator_response(performance, declared, options);
    return {response.written, response.compensated};
}

double lowest(const std::vector<double>& values, std::size_t from, std::size_t to) {
    return *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(from),
                             values.begin() + static_cast<std::ptrdiff_t>(to));
}

TEST(ActuatorDrives, LegatoAndPortamentoStayContinuousWhileTheDefaultSilenceIsFelt) {
    for (const Declaration& declared : {erm(), lra()}) {
        // Two quarter notes (200 ms each) from strength 1 to 0.5: tied, glided, or separated by
        // the default silence (30 ms at the first note's end).
        const auto legato = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"2\" legato=\"1\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\" legato=\"1\"/>",
            declared);
        const auto glide = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"1\" portamento=\"1\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\" portamento=\"1\"/>",
            declared);
        const auto apart = felt(
            "<Note length=\"quarter\" number=\"2\" string=\"2\"/>"
            "<Note length=\"quarter\" number=\"1\" string=\"3\"/>",
            declared);
        // Around the change (150..250 ms): tied notes never fall much below the lower level ...
        EXPECT_GT(lowest(legato.produced, 150, 250), 0.4);
        EXPECT_GT(lowest(glide.produced, 150, 250), 0.4);
        // ... the untied ones dip to less than half of the weaker note: a felt silence.
        EXPECT_LT(lowest(apart.produced, 150, 250), 0.25);
    }
}

TEST(ActuatorDrives, AHairpinIsFollowedStepByStep) {
    // A crescendo from silence to 1 over a half note (400 ms), then a decrescendo back to
    // silence over another: once the actuator has caught up (20 ms), it stays within a few
    // hundredths of the written ramp.
    for (const Declaration& declared : {erm(), lra()}) {
        const auto hairpin = felt(
            "<Note length=\"half\" number=\"2\" string=\"2\" dynamics=\"crescendo\" "
            "legato=\"1\"/>"
            "<Note length=\"half\" number=\"2\" string=\"2\" dynamics=\"decrescendo\" "
            "legato=\"1\"/>",
            declared);
        double worst = 0.0;
        for (std::size_t k = 20; k < 780; ++k) {
            worst = std::max(worst, std::abs(hairpin.produced[k] - hairpin.written[k]));
        }
        EXPECT_LT(worst, 0.05);
    }
}

TEST(ActuatorDrives, BrakeOnlyWhereTheBackendCanAndTheBoardIsDeclaredTo) {
    const std::vector<Cue> note{drive(0.0, 1.0), drive(0.5, 0.0)};
    const auto has_negative = [](const std::vector<Cue>& cues) {
        return std::any_of(cues.begin(), cues.end(), [](const Cue& c) { return c.amplitude < 0; });
    };
    EXPECT_TRUE(has_negative(adapt_cues(note, 1.0, declared(erm(Brake::reverse), true))));
    EXPECT_FALSE(has_negative(adapt_cues(note, 1.0, declared(erm(Brake::reverse), false))));
    EXPECT_FALSE(has_negative(adapt_cues(note, 1.0, declared(erm(Brake::none), true))));
}

TEST(ActuatorDrives, PositionsStayInTimeOrderAmongThePlannedDrives) {
    const auto cues =
        adapt_cues({drive(0.0, 1.0), position(0.0, 0), drive(0.2, 0.0), position(0.2, 1),
                    position(0.3, 2), drive(0.3, 0.8), drive(0.5, 0.0)},
                   0.5, declared(erm()));
    EXPECT_TRUE(std::is_sorted(cues.begin(), cues.end(),
                               [](const Cue& a, const Cue& b) { return a.at < b.at; }));
    EXPECT_EQ(std::count_if(cues.begin(), cues.end(),
                            [](const Cue& c) { return c.kind == Cue::Kind::position; }),
              3);
}

TEST(ActuatorDrives, OnlyTheLastPassBrakesBeyondItsEndAndTheNextPassGoesOnFromThere) {
    const std::vector<Cue> note{drive(0.0, 1.0), drive(0.1, 0.0)};  // ends where the pass ends
    auto carry = std::make_shared<PlannerCarry>();
    const auto first = adapt_cues(note, 0.1, declared(erm()));
    EXPECT_GT(first.back().at, 0.1);  // one pass, the last: the brake runs on after it

    AdaptedCueStream repeated(
        std::make_unique<CueListStream>(std::make_shared<const std::vector<Cue>>(note)), 0.1,
        declared(erm()), PassLink{carry, false});
    const auto pass = collect(repeated);
    for (const Cue& cue : pass) {
        EXPECT_LT(cue.at, 0.1);
    }
    EXPECT_NEAR(Physics::strength(carry->state), 1.0, 0.05);  // still spinning into the next pass

    // The next pass starts with a rest: it brakes what the last one left spinning.
    AdaptedCueStream next(std::make_unique<CueListStream>(std::make_shared<const std::vector<Cue>>(
                              std::vector<Cue>{drive(0.2, 1.0), drive(0.3, 0.0)})),
                          0.3, declared(erm()), PassLink{carry, true});
    const auto after = collect(next);
    ASSERT_FALSE(after.empty());
    EXPECT_EQ(after.front().at, 0.0);
    EXPECT_EQ(after.front().amplitude, -1.0);
}

TEST(ActuatorDrives, OnOffActuatorsGetOverdriveAndTheEarlyEndAsPulses) {
    CueAdaptation adaptation = declared(erm(Brake::none), false);
    adaptation.amplitude = false;
    const auto cues = adapt_cues({drive(0.0, 0.5), drive(0.4, 0.0)}, 0.4, adaptation);
    ASSERT_GE(cues.size(), 3u);
    // On without a break for the overdrive, longer than the first pulse of 0.35 x 40 ms would be.
    EXPECT_EQ(cues[0].amplitude, 1.0);
    EXPECT_GT(cues[1].at, 0.35 * 0.040);
    for (const auto& cue : cues) {
        EXPECT_TRUE(cue.amplitude == 0.0 || cue.amplitude == 1.0);
    }
    // The pulses stop early, spin-down x ln 2 before the written end (within the last pulse
    // period): the felt end is on time.
    const double cut = 0.4 - kDown * std::log(2.0);
    EXPECT_EQ(cues.back().amplitude, 0.0);
    EXPECT_LE(cues.back().at, cut + 1e-9);
    EXPECT_GT(cues.back().at, cut - adaptation.pulse_period_s);
}

}  // namespace
}  // namespace vibscore::render
