// A written clef fitted to a declared actuator (render::fit_clef): each rule of docs/clefs.md,
// each limit at its edge, and every shipped clef and score through the feel issue's ERM and LRA.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "actuator/physics.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/score_xml.hpp"
#include "tests/support/example_actuators.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore {
namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

using render::ClefFit;
using render::fit_clef;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

Clef sine_clef(std::vector<double> frequencies, std::vector<double> numbers = {0.2, 0.6, 1.0}) {
    Clef clef;
    clef.type = ClefType::sine;
    clef.tempo = 0.2;
    clef.numbers = std::move(numbers);
    for (const double f : frequencies) {
        clef.strings.push_back({f, {}});
    }
    return clef;
}

Clef lra_phone() {
    return sine_clef({155, 170, 185, 200, 215, 235});
}

Clef line_clef(std::vector<std::vector<ClefPoint>> strings, double tempo = 0.2) {
    Clef clef;
    clef.type = ClefType::line;
    clef.tempo = tempo;
    clef.numbers = {0.5, 1.0};
    for (auto& points : strings) {
        clef.strings.push_back({0.0, std::move(points)});
    }
    return clef;
}

double gain(const actuator::Declaration& d, double f) {
    return actuator::Physics(d).gain(f);
}

// --- the full-strength band ---

TEST(AFullStrengthBand, EndsWhereFullDriveGivesExactlyTheStrength) {
    const auto lra = example_lra();
    const auto band = render::full_strength_band(lra, 1.0);
    ASSERT_TRUE(band);
    EXPECT_NEAR(gain(lra, band->low_hz), 0.7, 1e-9);
    EXPECT_NEAR(gain(lra, band->high_hz), 0.7, 1e-9);
    EXPECT_LT(band->low_hz, 175.0);
    EXPECT_GT(band->high_hz, 175.0);
    // The "about +-6 Hz" of a phone LRA.
    EXPECT_NEAR(band->high_hz - band->low_hz, 12.0, 1.0);
}

TEST(AFullStrengthBand, IsTheResonanceAloneAtTheStrongestFullDriveGivesAndNothingBeyond) {
    const auto lra = example_lra();
    // Q 15 peaks a hair off f0 above 1: the strongest is 1/rated x that peak.
    const double peak = 1.0 / std::sqrt(1.0 - 1.0 / (4.0 * 15.0 * 15.0));
    const auto at = render::full_strength_band(lra, peak / 0.7 * (1.0 - 1e-9));
    ASSERT_TRUE(at);
    EXPECT_NEAR(at->high_hz / at->low_hz, 1.0, 1e-3);
    EXPECT_FALSE(render::full_strength_band(lra, peak / 0.7 * (1.0 + 1e-6)));
}

TEST(AFullStrengthBand, StaysWhereSkinFeelsPitch) {
    const auto band = render::full_strength_band(example_lra(175.0, 1.0), 0.1);
    ASSERT_TRUE(band);
    EXPECT_EQ(band->low_hz, render::kLowestPitchHz);
    EXPECT_EQ(band->high_hz, render::kHighestPitchHz);
}

TEST(AFullStrengthBand, DoesNotExistForAnErm) {
    EXPECT_FALSE(render::full_strength_band(example_erm(), 1.0));
}

// --- strings placed as pitch ---

TEST(FittingASineClef, SpreadsTheStringsAcrossAWideBandInTheirWrittenOrder) {
    const auto lra = example_lra(175.0, 1.5);
    const auto fit = fit_clef(lra_phone(), lra);
    ASSERT_EQ(fit.strings, ClefFit::Strings::pitch);
    ASSERT_TRUE(fit.band);
    ASSERT_EQ(fit.clef.strings.size(), 6u);
    EXPECT_EQ(fit.clef.type, ClefType::sine);
    EXPECT_NEAR(fit.clef.strings.front().frequency, fit.band->low_hz, 1e-9);
    EXPECT_NEAR(fit.clef.strings.back().frequency, fit.band->high_hz, 1e-9);
    for (std::size_t s = 1; s < 6; ++s) {
        EXPECT_GE(fit.clef.strings[s].frequency / fit.clef.strings[s - 1].frequency,
                  render::kDistinctPitchRatio);
    }
    for (const auto& string : fit.clef.strings) {
        EXPECT_GE(gain(lra, string.frequency) / 0.7, 1.0 - 1e-9) << string.frequency;
    }
    EXPECT_THAT(fit.notes.front(), HasSubstr("strings spread"));
}

TEST(FittingASineClef, KeepsTheWrittenOrderWhenItIsNotAscending) {
    const auto fit = fit_clef(sine_clef({235, 155, 200}), example_lra(175.0, 1.5));
    ASSERT_EQ(fit.strings, ClefFit::Strings::pitch);
    EXPECT_GT(fit.clef.strings[0].frequency, fit.clef.strings[2].frequency);
    EXPECT_GT(fit.clef.strings[2].frequency, fit.clef.strings[1].frequency);
}

TEST(FittingASineClef, LeavesStringsTheActuatorAlreadyPlaysAsWritten) {
    const Clef written = sine_clef({60, 100, 180});
    const auto fit = fit_clef(written, example_lra(175.0, 1.5));
    EXPECT_EQ(fit.strings, ClefFit::Strings::as_written);
    EXPECT_EQ(fit.clef, written);
    EXPECT_THAT(fit.notes, IsEmpty());
    EXPECT_FALSE(fit.changed());
}

TEST(FittingASineClef, MovesStringsThatAreInTheBandButTooClose) {
    const auto fit = fit_clef(sine_clef({150, 170, 220}), example_lra(175.0, 1.5));
    EXPECT_EQ(fit.strings, ClefFit::Strings::pitch);
}

TEST(FittingASineClef, PlacesAsManyDistinctStringsAsTheBandHoldsAndTurnsOneMoreIntoRoughness) {
    const auto lra = example_lra(175.0, 3.0);
    const auto band = render::full_strength_band(lra, 1.0);
    ASSERT_TRUE(band);
    const auto fits = static_cast<std::size_t>(std::floor(std::log(band->high_hz / band->low_hz) /
                                                          std::log(render::kDistinctPitchRatio))) +
                      1;
    ASSERT_GE(fits, 2u);
    ASSERT_LT(fits, 6u);
    std::vector<double> strings;
    for (std::size_t s = 0; s < fits; ++s) {
        strings.push_back(100.0 + 5.0 * static_cast<double>(s));
    }
    EXPECT_EQ(fit_clef(sine_clef(strings), lra).strings, ClefFit::Strings::pitch);
    strings.push_back(300.0);
    EXPECT_EQ(fit_clef(sine_clef(strings), lra).strings, ClefFit::Strings::roughness);
}

TEST(FittingASineClef, PutsALoneStringOutsideTheBandAtResonance) {
    const auto fit = fit_clef(sine_clef({235}), example_lra());
    ASSERT_EQ(fit.strings, ClefFit::Strings::pitch);
    EXPECT_EQ(fit.clef.strings[0].frequency, 175.0);
}

TEST(FittingASineClef, WithoutCompensationPlacesStringsWhereRatedDriveKeepsNinetyPercent) {
    auto lra = example_lra(175.0, 1.0);
    lra.compensation = false;
    const auto fit = fit_clef(lra_phone(), lra);
    ASSERT_EQ(fit.strings, ClefFit::Strings::pitch);
    for (const auto& string : fit.clef.strings) {
        EXPECT_GE(gain(lra, string.frequency), render::kUncompensatedGain - 1e-9);
    }
}

// --- roughness ---

TEST(FittingASineClef, TurnsStringsIntoRoughnessOnAHighQLra) {
    const auto fit = fit_clef(lra_phone(), example_lra());
    ASSERT_EQ(fit.strings, ClefFit::Strings::roughness);
    EXPECT_EQ(fit.clef.type, ClefType::line);
    EXPECT_EQ(fit.clef.tempo, 0.2);
    ASSERT_EQ(fit.clef.strings.size(), 6u);
    ASSERT_EQ(fit.periods_s.size(), 6u);
    EXPECT_THAT(fit.notes.back(), HasSubstr("too narrow for 6 strings"));
    EXPECT_THAT(fit.notes.back(), HasSubstr("roughness"));
}

TEST(FittingASineClef, TurnsStringsIntoRoughnessOnAnErm) {
    const auto fit = fit_clef(lra_phone(), example_erm());
    ASSERT_EQ(fit.strings, ClefFit::Strings::roughness);
    EXPECT_THAT(fit.notes.back(), HasSubstr("an ERM has no pitch"));
}

TEST(RoughnessPeriods, AreTheThesisPeriodsOnAnActuatorFastEnough) {
    auto quick = example_erm();
    quick.spin_up_s = 0.001;
    const auto periods = render::roughness_periods_s(quick, 6, 1.0);
    const std::vector<double> thesis{0.120, 0.100, 0.080, 0.060, 0.040, 0.020};
    ASSERT_EQ(periods.size(), 6u);
    for (std::size_t s = 0; s < 6; ++s) {
        EXPECT_NEAR(periods[s], thesis[s], 1e-12) << "string " << s + 1;
    }
}

TEST(RoughnessPeriods, LengthenSoTheActuatorReachesFullStrengthInHalfAPeriod) {
    for (const auto& d : {example_erm(), example_lra()}) {
        const auto periods = render::roughness_periods_s(d, 6, 1.0);
        const double reach = render::time_to_strength_s(d, 1.0);
        EXPECT_GT(reach, 0.010);  // neither follows the thesis' 20 ms
        EXPECT_GE(periods.back(), 2.0 * reach);
        EXPECT_LT(periods.back(), 2.0 * reach + 0.001);  // a whole millisecond
        for (std::size_t s = 0; s + 1 < periods.size(); ++s) {
            EXPECT_GE(periods[s] / periods[s + 1], render::kDistinctPitchRatio - 1e-12);
            EXPECT_GE(periods[s], render::kRoughestPeriodS - 0.020 * static_cast<double>(s));
        }
    }
}

TEST(RoughnessPeriods, KeepTheThesisPeriodWhereItIsJustLongEnough) {
    auto d = example_erm();
    d.spin_up_s = 0.001;
    // The shortest thesis period (20 ms) against a reach of just under and just over 10 ms.
    const double per_constant = render::time_to_strength_s(d, 1.0) / 0.001;
    d.spin_up_s = 0.010 / per_constant * (1.0 - 1e-6);
    EXPECT_DOUBLE_EQ(render::roughness_periods_s(d, 6, 1.0).back(), 0.020);
    d.spin_up_s = 0.010 / per_constant * (1.0 + 1e-6);
    EXPECT_GT(render::roughness_periods_s(d, 6, 1.0).back(), 0.020);
}

TEST(RoughnessPeriods, AreNoneForALoneString) {
    EXPECT_THAT(render::roughness_periods_s(example_erm(), 1, 1.0), IsEmpty());
    const auto fit = fit_clef(sine_clef({200}), example_erm());
    ASSERT_EQ(fit.clef.strings.size(), 1u);
    EXPECT_EQ(fit.clef.strings[0].points, (std::vector<ClefPoint>{{0.0, 1.0}, {1.0, 1.0}}));
}

TEST(ARoughnessString, IsAHalfOnHalfOffSquareWaveOfItsPeriod) {
    auto quick = example_erm();
    quick.spin_up_s = 0.001;
    const auto fit = fit_clef(lra_phone(), quick);
    // String 6, 20 ms at a 0.2 s quarter: ten periods, on for the first 10 ms of each.
    const auto& points = fit.clef.strings[5].points;
    ASSERT_EQ(points.size(), 40u);
    EXPECT_EQ(points[0], (ClefPoint{0.0, 1.0}));
    EXPECT_NEAR(points[1].time, 0.05, 1e-12);
    EXPECT_EQ(points[1].level, 1.0);
    EXPECT_NEAR(points[2].time, 0.05, 1e-12);
    EXPECT_EQ(points[2].level, 0.0);
    EXPECT_EQ(points.back().time, 1.0);
    // And it reads back as a clef.
    EXPECT_EQ(read_clef(write_clef(fit.clef), "fitted"), fit.clef);
}

TEST(ARoughnessString, ThatCannotBeWrittenIsRefusedNamingTheString) {
    auto quick = example_erm();
    quick.spin_up_s = 0.001;
    Clef clef = lra_phone();
    // 20 ms periods: 2048 halves of 10 ms fit a 20.48 s quarter, one more does not.
    clef.tempo = 20.48;
    EXPECT_NO_THROW(fit_clef(clef, quick));
    clef.tempo = 20.49;
    try {
        fit_clef(clef, quick);
        FAIL() << "fitted";
    } catch (const render::ClefFitError& e) {
        EXPECT_THAT(e.what(), HasSubstr("string 6"));
        EXPECT_THAT(e.what(), HasSubstr("4096 points"));
    }
}

// --- numbers ---

TEST(FittingAClef, KeepsTheNumbersStrengths) {
    for (const auto& d : {example_erm(), example_lra(), example_lra(175.0, 1.5)}) {
        EXPECT_EQ(fit_clef(lra_phone(), d).clef.numbers, lra_phone().numbers);
    }
}

TEST(FittingAClef, BringsANumberBeyondFullDriveDownToFullDriveAndSaysSo) {
    const double full = 1.0 / 0.7;
    const auto kept = fit_clef(sine_clef({175}, {0.5, full}), example_erm());
    EXPECT_EQ(kept.clef.numbers[1], full);
    const auto cut = fit_clef(sine_clef({175}, {0.5, full * (1.0 + 1e-9), 2.0}), example_erm());
    EXPECT_DOUBLE_EQ(cut.clef.numbers[1], full);
    EXPECT_DOUBLE_EQ(cut.clef.numbers[2], full);
    EXPECT_THAT(cut.notes[1], HasSubstr("number 3: strength 2 is beyond full drive"));
}

// --- shapes ---

TEST(AShapeWiggle, IsARampUpIntoARampDown) {
    const ClefString tent{0.0, {{0.0, 0.0}, {0.05, 1.0}, {0.2, 0.0}}};
    ASSERT_TRUE(render::shortest_wiggle(tent));
    EXPECT_DOUBLE_EQ(*render::shortest_wiggle(tent), 0.05);
}

TEST(AShapeWiggle, IsNotAStepNorAHoldNorARipple) {
    const ClefString square{0.0, {{0.0, 1.0}, {0.05, 1.0}, {0.05, 0.0}, {0.1, 0.0}}};
    EXPECT_FALSE(render::shortest_wiggle(square));
    const ClefString held{0.0, {{0.0, 0.0}, {0.01, 1.0}, {0.5, 1.0}, {0.51, 0.0}}};
    EXPECT_FALSE(render::shortest_wiggle(held));
    const ClefString ripple{0.0, {{0.0, 0.5}, {0.01, 0.54}, {0.02, 0.5}}};
    EXPECT_FALSE(render::shortest_wiggle(ripple));
}

TEST(FittingAShapeClef, SmoothsAWiggleTheErmCannotFollowAndSaysSo) {
    // A 10 ms tent on a 0.2 s quarter: 5 ms up, 5 ms down.
    const Clef written =
        line_clef({{{0.0, 0.0}, {0.025, 1.0}, {0.05, 0.0}, {1.0, 0.0}}, {{0.0, 0.5}, {1.0, 0.5}}});
    const auto erm = example_erm();
    const auto fit = fit_clef(written, erm);
    ASSERT_EQ(fit.strings, ClefFit::Strings::smoothed);
    ASSERT_EQ(fit.notes.size(), 1u);
    EXPECT_THAT(fit.notes[0], HasSubstr("string 1: a 5 ms rise or fall is faster than the ERM"));
    EXPECT_EQ(fit.clef.strings[1], written.strings[1]);
    const auto& smooth = fit.clef.strings[0].points;
    double peak = 0.0, area = 0.0;
    for (std::size_t p = 1; p < smooth.size(); ++p) {
        peak = std::max(peak, smooth[p].level);
        area += (smooth[p].time - smooth[p - 1].time) * (smooth[p].level + smooth[p - 1].level) / 2;
    }
    EXPECT_LT(peak, 0.6);              // what an ERM would have made of it anyway
    EXPECT_NEAR(area, 0.025, 0.0025);  // the drive it asks is kept
    EXPECT_FALSE(render::shortest_wiggle(fit.clef.strings[0]) &&
                 *render::shortest_wiggle(fit.clef.strings[0]) * written.tempo <
                     render::shortest_followed_s(erm, 1.0));
    EXPECT_EQ(read_clef(write_clef(fit.clef), "fitted"), fit.clef);
}

TEST(FittingAShapeClef, KeepsAWiggleJustSlowEnoughAndSmoothsOneJustTooFast) {
    const auto erm = example_erm();
    const double follows = render::shortest_followed_s(erm, 1.0) / 0.2;  // normalised
    const auto tent = [](double half) {
        return line_clef({{{0.0, 0.0}, {half, 1.0}, {2.0 * half, 0.0}, {1.0, 0.0}}});
    };
    EXPECT_EQ(fit_clef(tent(follows * 1.001), erm).strings, ClefFit::Strings::as_written);
    EXPECT_EQ(fit_clef(tent(follows * 0.999), erm).strings, ClefFit::Strings::smoothed);
}

TEST(FittingAShapeClef, KeepsSquareWavesTheyAreDeliberateOnOffDrive) {
    auto clefs = std::filesystem::path(testing::required_env("VIBSCORE_CLEFS"));
    const Clef rough = load_clef_file(clefs / "erm-rough.clef.xml");
    const auto fit = fit_clef(rough, example_erm());
    EXPECT_EQ(fit.strings, ClefFit::Strings::as_written);
    EXPECT_EQ(fit.clef, rough);
}

// --- every shipped clef and score ---

std::vector<std::filesystem::path> shipped(const char* suffix) {
    std::vector<std::filesystem::path> found;
    for (const auto& entry :
         std::filesystem::directory_iterator(testing::required_env("VIBSCORE_CLEFS"))) {
        if (entry.path().filename().string().ends_with(suffix)) {
            found.push_back(entry.path());
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

TEST(ShippedClefs, EachFitsBothExampleActuatorsAndReadsBack) {
    const auto clefs = shipped(".clef.xml");
    ASSERT_GE(clefs.size(), 9u);
    for (const auto& d : {example_erm(), example_lra()}) {
        for (const auto& path : clefs) {
            const Clef written = load_clef_file(path);
            const auto fit = fit_clef(written, d);
            EXPECT_EQ(fit.clef.strings.size(), written.strings.size()) << path;
            EXPECT_EQ(fit.clef.numbers, written.numbers) << path;
            EXPECT_EQ(fit.clef.tempo, written.tempo) << path;
            EXPECT_EQ(read_clef(write_clef(fit.clef), path.string()), fit.clef) << path;
            if (fit.strings == ClefFit::Strings::pitch) {
                for (std::size_t s = 1; s < fit.frequencies_hz.size(); ++s) {
                    const double a = fit.frequencies_hz[s - 1], b = fit.frequencies_hz[s];
                    EXPECT_GE(std::max(a, b) / std::min(a, b), render::kDistinctPitchRatio - 1e-9);
                }
            }
        }
    }
}

TEST(ShippedClefs, LraPhoneBecomesRoughnessOnBothExampleActuators) {
    const auto path = shipped(".clef.xml");
    const auto lra_phone_path = std::find_if(path.begin(), path.end(), [](const auto& p) {
        return p.filename() == "lra-phone.clef.xml";
    });
    ASSERT_NE(lra_phone_path, path.end());
    const Clef written = load_clef_file(*lra_phone_path);
    EXPECT_EQ(fit_clef(written, example_lra()).strings, ClefFit::Strings::roughness);
    EXPECT_EQ(fit_clef(written, example_erm()).strings, ClefFit::Strings::roughness);
}

TEST(ShippedScores, EachStaysValidThroughItsFittedClefs) {
    const auto scores = shipped(".score.xml");
    ASSERT_GE(scores.size(), 20u);
    for (const auto& d : {example_erm(), example_lra()}) {
        for (const auto& path : scores) {
            const ScoreBundle written = load_score_file(path);
            EXPECT_NO_THROW(bind_clefs(read_score(read_document_file(path), path.string()),
                                       path.string(),
                                       [&](const ClefDeclaration& declared, const SourceLocation&) {
                                           return fit_clef(written.clefs.at(declared.id), d).clef;
                                       }))
                << path;
        }
    }
}

}  // namespace
}  // namespace vibscore
