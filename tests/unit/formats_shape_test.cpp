// Issue 31 item 2: an import keeps the shape of what it imports. Judged by what plays: the
// imported score is rendered and its envelope compared with the curve the file asks for.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>

#include "client/formats/ahap.hpp"
#include "client/formats/android.hpp"
#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/limits.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;

formats::ChosenClef lra_phone() {
    const auto path =
        std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / "lra-phone.clef.xml";
    return {"lra-phone", load_clef_file(path)};
}

ScoreBundle bound(const formats::ImportedScore& imported) {
    ParsedScore parsed{imported.score, {}};
    parsed.where.clefs.resize(imported.score.clefs.size());
    for (const auto& bar : imported.score.bars) {
        parsed.where.bars.emplace_back();
        parsed.where.symbols.emplace_back(bar.symbols.size());
    }
    return bind_clefs(std::move(parsed), "imported",
                      [&](const ClefDeclaration& declaration, const auto&) {
                          for (const auto& clef : imported.clefs) {
                              if (clef.id == declaration.id) {
                                  return clef.clef;
                              }
                          }
                          throw DocumentError({"imported"}, "no clef " + declaration.id);
                      });
}

// The rendered envelope, 0..1 of the strongest number, every millisecond.
struct Envelope {
    std::vector<double> levels;
    double step = 0.001;

    double at(double t) const { return levels.at(static_cast<std::size_t>(std::lround(t / step))); }
    double peak_time() const {
        return static_cast<double>(std::max_element(levels.begin(), levels.end()) -
                                   levels.begin()) *
               step;
    }
    double peak() const { return *std::max_element(levels.begin(), levels.end()); }
};

Envelope rendered(const formats::ImportedScore& imported) {
    const auto bundle = bound(imported);
    const render::Performance performance(bundle);
    double strongest = 0.0;
    for (const double amplitude : lra_phone().clef.numbers) {
        strongest = std::max(strongest, amplitude);
    }
    Envelope envelope;
    for (double t = 0.0; t < performance.duration(); t += envelope.step) {
        envelope.levels.push_back(performance.envelope_at(t) / strongest);
    }
    return envelope;
}

// One continuous event of `seconds` at full intensity under one intensity curve.
std::string curve_pattern(double seconds, const std::vector<std::pair<double, double>>& points) {
    nlohmann::json control = nlohmann::json::array();
    for (const auto& [at, value] : points) {
        control.push_back({{"Time", at}, {"ParameterValue", value}});
    }
    nlohmann::json pattern = nlohmann::json::array();
    pattern.push_back({{"Event",
                        {{"Time", 0.0},
                         {"EventType", "HapticContinuous"},
                         {"EventDuration", seconds},
                         {"EventParameters",
                          {{{"ParameterID", "HapticIntensity"}, {"ParameterValue", 1.0}},
                           {{"ParameterID", "HapticSharpness"}, {"ParameterValue", 0.4}}}}}}});
    pattern.push_back({{"ParameterCurve",
                        {{"ParameterID", "HapticIntensityControl"},
                         {"Time", 0.0},
                         {"ParameterCurveControlPoints", control}}}});
    return nlohmann::json{{"Version", 1.0}, {"Pattern", pattern}}.dump();
}

// The curve's value at t: linear between its points.
double curve_at(const std::vector<std::pair<double, double>>& points, double t) {
    for (std::size_t i = 1; i < points.size(); ++i) {
        if (t <= points[i].first) {
            const auto& [t0, v0] = points[i - 1];
            const auto& [t1, v1] = points[i];
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
        }
    }
    return points.back().second;
}

constexpr double kThirtySecond = 0.2 / 8;  // lra-phone's tempo, which the event's times fit
// lra-phone's numbers lie 0.1 of full apart: a level is at most half of that from a number, and
// a ramp between numbers may be that far from the curve's.
constexpr double kLevelTolerance = 0.1;

TEST(AhapShape, ARiseAndFallPeaksWhereTheCurvePeaksAndKeepsItsFall) {
    const std::vector<std::pair<double, double>> curve{{0.0, 0.2}, {0.25, 1.0}, {0.5, 0.3}};
    const auto imported = formats::read_ahap(curve_pattern(0.5, curve), "peak.ahap", lra_phone());
    const auto envelope = rendered(imported);
    EXPECT_NEAR(envelope.peak_time(), 0.25, kThirtySecond);
    EXPECT_NEAR(envelope.peak(), 1.0, kLevelTolerance);
    // The fall is kept: down through the middle of it to near the curve's end level.
    EXPECT_NEAR(envelope.at(0.375), curve_at(curve, 0.375), kLevelTolerance);
    EXPECT_NEAR(envelope.at(0.5 - kThirtySecond - 0.002), 0.3 + 0.7 * (kThirtySecond / 0.25),
                kLevelTolerance);
    EXPECT_LT(envelope.at(0.49), 0.45);
    // Everywhere but a 32nd around the bends, the envelope is the curve.
    for (double t = 0.005; t < 0.495; t += 0.005) {
        if (std::abs(t - 0.25) > kThirtySecond && t < 0.5 - kThirtySecond) {
            EXPECT_NEAR(envelope.at(t), curve_at(curve, t), kLevelTolerance) << "at " << t << " s";
        }
    }
    // What could not be drawn exactly is said.
    ASSERT_FALSE(imported.warnings.empty());
    EXPECT_THAT(imported.warnings.back().message,
                HasSubstr("its intensity curve, in 2 straight pieces, is tied notes"));
    EXPECT_THAT(imported.warnings.back().message, HasSubstr("the event at 0 s"));
}

TEST(AhapShape, ARiseOnlyCurveReachesFullWhereItEndsNotAPartEarly) {
    // 0.5 s at lra-phone's 0.2 s quarter is a half and an 8th, tied: the rise spans both.
    const std::vector<std::pair<double, double>> curve{{0.0, 0.0}, {0.5, 1.0}};
    const auto envelope =
        rendered(formats::read_ahap(curve_pattern(0.5, curve), "rise.ahap", lra_phone()));
    EXPECT_NEAR(envelope.peak_time(), 0.5, kThirtySecond);
    for (double t = 0.01; t < 0.49; t += 0.01) {
        EXPECT_NEAR(envelope.at(t), curve_at(curve, t), kLevelTolerance) << "at " << t << " s";
    }
}

TEST(AhapShape, AFallOnlyCurveFallsAcrossTheWholeNote) {
    const std::vector<std::pair<double, double>> curve{{0.0, 1.0}, {0.5, 0.0}};
    const auto envelope =
        rendered(formats::read_ahap(curve_pattern(0.5, curve), "fall.ahap", lra_phone()));
    EXPECT_NEAR(envelope.peak_time(), 0.0, kThirtySecond);
    for (double t = 0.01; t < 0.49; t += 0.01) {
        EXPECT_NEAR(envelope.at(t), curve_at(curve, t), kLevelTolerance) << "at " << t << " s";
    }
}

TEST(AhapShape, ACurveWithSeveralBendsKeepsEachPeakAndDip) {
    const std::vector<std::pair<double, double>> curve{
        {0.0, 0.3}, {0.2, 0.9}, {0.4, 0.4}, {0.6, 1.0}, {0.8, 0.5}};
    const auto imported = formats::read_ahap(curve_pattern(0.8, curve), "waves.ahap", lra_phone());
    const auto envelope = rendered(imported);
    EXPECT_NEAR(envelope.peak_time(), 0.6, kThirtySecond);
    EXPECT_NEAR(envelope.at(0.2), 0.9, kLevelTolerance);
    EXPECT_NEAR(envelope.at(0.4), 0.4, kLevelTolerance);
    for (double t = 0.01; t < 0.8 - kThirtySecond; t += 0.01) {
        EXPECT_NEAR(envelope.at(t), curve_at(curve, t), kLevelTolerance) << "at " << t << " s";
    }
}

TEST(AhapShape, AStraightCurveStaysOneNoteWithAHairpinAndSaysNothing) {
    const std::vector<std::pair<double, double>> curve{{0.0, 0.0}, {0.2, 0.5}, {0.4, 1.0}};
    const auto imported =
        formats::read_ahap(curve_pattern(0.4, curve), "straight.ahap", lra_phone());
    ASSERT_EQ(imported.score.bars.size(), 1u);
    ASSERT_EQ(imported.score.bars[0].symbols.size(), 1u);
    EXPECT_EQ(std::get<Note>(imported.score.bars[0].symbols[0]).dynamics, Dynamics::crescendo);
    EXPECT_TRUE(imported.warnings.empty());
}

// Looking at each bend inside each event costs events x bends: events sounding together (a few
// bytes each) could make that years. A score holds at most limits::symbols symbols, and each
// bend is one note at least, so the reader looks at that many bends and refuses the next.
TEST(AhapShape, ReadsAHundredThousandBendsWithinEventsAndRefusesOneMore) {
    const auto pattern = [](int events, bool one_more) {
        std::string text = R"({"Pattern": [)";
        for (int e = 0; e < events; ++e) {
            text +=
                R"({"Event": {"Time": 0, "EventType": "HapticContinuous", "EventDuration": 1}},)";
        }
        if (one_more) {  // over the first bend only
            text +=
                R"({"Event": {"Time": 0, "EventType": "HapticContinuous", "EventDuration": 0.06}},)";
        }
        text += R"({"ParameterCurve": {"ParameterID": "HapticIntensityControl", "Time": 0,
                   "ParameterCurveControlPoints": [)";
        for (int k = 1; k <= 10; ++k) {  // ten bends, at 0.05 s to 0.5 s
            text += std::string(k > 1 ? "," : "") + R"({"Time": )" + std::to_string(0.05 * k) +
                    R"(, "ParameterValue": )" + (k % 2 == 0 ? "1.0" : "0.2") + "}";
        }
        return text + "]}}]}";
    };
    static_assert(limits::symbols == 100000);
    EXPECT_NO_THROW(formats::read_ahap(pattern(10000, false), "many.ahap", lra_phone()));
    try {
        formats::read_ahap(pattern(10000, true), "many.ahap", lra_phone());
        ADD_FAILURE() << "a hundred thousand and one bends were read";
    } catch (const DocumentError& error) {
        EXPECT_THAT(error.what(), HasSubstr("bend more than 100000 times within events"));
    }
}

// Android's envelope: ramps 0.2 -> 1.0 -> 0.3 between sounding levels, after a 1 ms attack and
// before a 1 ms release, are no hairpins (a crescendo rises from silence, a decrescendo falls
// to it): they come back as glides that start and end at those levels.
TEST(AndroidShape, RampsBetweenSoundingLevelsPlayFromAndToThoseLevels) {
    const std::string text = R"(<vibration-effect>
  <waveform-envelope-effect initialFrequencyHz="155">
    <control-point amplitude="0.2" frequencyHz="155" durationMs="1"/>
    <control-point amplitude="1.0" frequencyHz="155" durationMs="250"/>
    <control-point amplitude="0.3" frequencyHz="155" durationMs="250"/>
    <control-point amplitude="0.0" frequencyHz="155" durationMs="1"/>
  </waveform-envelope-effect>
</vibration-effect>)";
    const auto imported = formats::read_android_xml(text, "ramps.xml", lra_phone());
    // Whole milliseconds choose a grid of 1 ms (a tempo of 8 ms), where the last part of the
    // glide up, 3 ms long, already has the top number (0.976 of full is nearest 1.0): a 32nd or
    // the 5 ms of a 32nd at a tempo a person would write, whichever is longer.
    const double thirty_second = std::max(imported.clefs.front().clef.tempo / 8, 0.005);
    const auto envelope = rendered(imported);
    // The curve the file asks for, from the end of its attack to the start of its release.
    const std::vector<std::pair<double, double>> curve{{0.0, 0.2}, {0.251, 1.0}, {0.501, 0.3}};
    EXPECT_NEAR(envelope.peak_time(), 0.251, thirty_second);
    EXPECT_NEAR(envelope.peak(), 1.0, kLevelTolerance);
    for (double t = 0.005; t < 0.501 - thirty_second; t += 0.005) {
        if (std::abs(t - 0.251) > thirty_second) {
            EXPECT_NEAR(envelope.at(t), curve_at(curve, t), kLevelTolerance) << "at " << t << " s";
        }
    }
}

// An export of a score ending in a rest lasts as long as the score: Core Haptics counts a
// pattern to its last event's end or its last parameter's start, whichever is later.
TEST(AhapShape, AnExportOfAScoreEndingInARestPlaysAsLongAsTheScore) {
    const auto chosen = lra_phone();
    // Two quarter notes, then rest to the end of four bars of four: 3.2 s at 0.2 s a quarter.
    const auto score =
        formats::build_score({{0, 8, 1, 9}, {16, 8, 1, 5}}, {{0, 0.2}},
                             4 * 4 * formats::ticks_per_quarter, chosen, "loop", "loop.score.xml");
    const auto original = bound(score);
    const render::Performance before(original);
    ASSERT_DOUBLE_EQ(before.duration(), 3.2);
    const auto text = formats::write_ahap(formats::sound_track(original));
    const auto back = bound(formats::read_ahap(text, "loop.ahap", chosen));
    EXPECT_NEAR(render::Performance(back).duration(), 3.2, 1e-9);
}

}  // namespace
}  // namespace vibscore
