// Play's pure step, without a bus: every option and every bad value, the score found by name or
// sent inline, a clef override, and the request the player gets.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "daemon/play_request.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "daemon/request_error.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using Options = std::map<std::string, sdbus::Variant>;

// The message of the RequestError `body` throws, after checking its code.
template <typename Body>
std::string refusal(RequestError::Code code, Body&& body) {
    try {
        body();
    } catch (const RequestError& error) {
        EXPECT_EQ(error.code(), code) << error.what();
        return error.what();
    }
    ADD_FAILURE() << "no RequestError thrown";
    return {};
}

// One pass of a request's cues, as the player reads them.
std::vector<render::Cue> cues_of(const PlaybackRequest& request) {
    return render::collect(*request.cues->pass());
}

std::string invalid_options(const Options& options) {
    return refusal(RequestError::Code::invalid, [&] { parse_play_options(options); });
}

std::string out_of_range_options(const Options& options) {
    return refusal(RequestError::Code::out_of_range, [&] { parse_play_options(options); });
}

TEST(PlayOptions, NoOptionsMeanANotificationPlayedOnceAtFullStrengthThroughItsOwnClefs) {
    const PlayOptions options = parse_play_options({});
    EXPECT_EQ(options.usage, Usage::notification);
    EXPECT_EQ(options.repeat, 0);
    EXPECT_EQ(options.intensity, 1.0);
    EXPECT_EQ(options.clef, "");
    EXPECT_EQ(options.start_bar, 0u);
}

TEST(PlayOptions, EachOptionIsTakenInItsDBusType) {
    const PlayOptions options = parse_play_options({
        {"usage", sdbus::Variant(std::string("ringtone"))},
        {"repeat", sdbus::Variant(std::int32_t{3})},
        {"intensity", sdbus::Variant(0.25)},
        {"clef", sdbus::Variant(std::string("erm-phone"))},
        {"start-bar", sdbus::Variant(std::uint32_t{2})},
    });
    EXPECT_EQ(options.usage, Usage::ringtone);
    EXPECT_EQ(options.repeat, 3);
    EXPECT_EQ(options.intensity, 0.25);
    EXPECT_EQ(options.clef, "erm-phone");
    EXPECT_EQ(options.start_bar, 2u);
}

TEST(PlayOptions, EveryUsageIsKnownByItsName) {
    for (const auto* name : {"ringtone", "alarm", "notification", "communication", "accessibility",
                             "hardware-feedback", "touch", "media"}) {
        const auto options = parse_play_options({{"usage", sdbus::Variant(std::string(name))}});
        EXPECT_EQ(to_string(options.usage), name);
    }
}

TEST(PlayOptions, AnUnknownUsageIsRefusedListingTheKnownOnes) {
    const auto message = invalid_options({{"usage", sdbus::Variant(std::string("loud"))}});
    EXPECT_THAT(message, HasSubstr("unknown usage \"loud\""));
    EXPECT_THAT(message, HasSubstr("ringtone"));
    EXPECT_THAT(message, HasSubstr("media"));
}

TEST(PlayOptions, RepeatTakesMinusOneForeverButNothingBelowWhichIsOutOfRange) {
    EXPECT_EQ(parse_play_options({{"repeat", sdbus::Variant(std::int32_t{-1})}}).repeat, -1);
    EXPECT_THAT(out_of_range_options({{"repeat", sdbus::Variant(std::int32_t{-2})}}),
                HasSubstr("repeat -2 is outside -1.. (0 once, n more times, -1 until stopped)"));
}

TEST(PlayOptions, AnIntensityOutsideZeroToOneIsOutOfRangeAtBothEdges) {
    EXPECT_EQ(parse_play_options({{"intensity", sdbus::Variant(0.0)}}).intensity, 0.0);
    EXPECT_EQ(parse_play_options({{"intensity", sdbus::Variant(1.0)}}).intensity, 1.0);
    const double below_zero = -std::numeric_limits<double>::denorm_min();
    const double above_one = std::nextafter(1.0, 2.0);
    for (const double bad :
         {below_zero, -0.01, above_one, 1.0000001, 1.01, std::numeric_limits<double>::quiet_NaN(),
          std::numeric_limits<double>::infinity()}) {
        EXPECT_THAT(out_of_range_options({{"intensity", sdbus::Variant(bad)}}),
                    HasSubstr("is outside 0..1"))
            << bad;
    }
}

TEST(PlayOptions, AValueOfTheWrongTypeIsRefusedNamingBothTypes) {
    EXPECT_THAT(invalid_options({{"usage", sdbus::Variant(std::int32_t{1})}}),
                HasSubstr("option \"usage\" must be a string (s), not i"));
    EXPECT_THAT(invalid_options({{"repeat", sdbus::Variant(std::uint32_t{1})}}),
                HasSubstr("option \"repeat\" must be an int32 (i), not u"));
    EXPECT_THAT(invalid_options({{"intensity", sdbus::Variant(std::int32_t{1})}}),
                HasSubstr("option \"intensity\" must be a double (d), not i"));
    EXPECT_THAT(invalid_options({{"clef", sdbus::Variant(std::int32_t{1})}}),
                HasSubstr("option \"clef\" must be a string (s), not i"));
    EXPECT_THAT(invalid_options({{"start-bar", sdbus::Variant(std::int32_t{1})}}),
                HasSubstr("option \"start-bar\" must be a uint32 (u), not i"));
}

TEST(PlayOptions, AnUnknownOptionIsRefusedListingTheKnownOnes) {
    EXPECT_THAT(invalid_options({{"volume", sdbus::Variant(1.0)}}),
                HasSubstr("unknown option \"volume\" (expected usage, repeat, intensity, clef, "
                          "start-bar, clefs)"));
}

class ScoreToPlayTest : public ::testing::Test {
  protected:
    vibscore::testing::TempDir store;
    Registry registry{vibscore::testing::required_env("VIBSCORE_CLEFS"), store.path()};

    static std::string inline_score() {
        return "\n  <VibScore version=\"1.0\"><Title>inline</Title>"
               "<Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
               "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"5\" string=\"3\"/>"
               "<Note length=\"quarter\" number=\"7\" string=\"4\"/></Bar>"
               "<Bar clef=\"lra\"><Note length=\"half\" number=\"9\" string=\"6\"/></Bar>"
               "</VibScore>";
    }
};

TEST_F(ScoreToPlayTest, ARegistryScoreIsFoundByNameAndLabelledWithIt) {
    const auto found = find_score_to_play(registry, "ringtone", {});
    EXPECT_EQ(found.label, "ringtone");
    EXPECT_EQ(found.bundle.score.bars.size(), registry.score("ringtone").score.bars.size());
}

TEST_F(ScoreToPlayTest, TextStartingWithAnElementIsAnInlineDocumentOnRegistryClefs) {
    const auto found = find_score_to_play(registry, inline_score(), {});
    EXPECT_EQ(found.label, "<inline>");
    ASSERT_EQ(found.bundle.score.bars.size(), 2u);
    EXPECT_EQ(found.bundle.clefs.at("lra").tempo, registry.clef("lra-phone").tempo);
}

TEST_F(ScoreToPlayTest, AMissingScoreOrOverrideClefIsNotFound) {
    const auto code_of = [&](const std::string& score, const std::string& clef) {
        try {
            find_score_to_play(registry, score, PlayOptions{.clef = clef});
        } catch (const RegistryError& error) {
            return error.code();
        }
        return RegistryError::Code::in_use;  // anything but the expected code
    };
    EXPECT_EQ(code_of("no-such-score", ""), RegistryError::Code::not_found);
    EXPECT_EQ(code_of("ringtone", "no-such-clef"), RegistryError::Code::not_found);
}

TEST_F(ScoreToPlayTest, AClefOverrideReplacesEveryClefTheScoreDeclares) {
    const auto own = find_score_to_play(registry, "delete-folder", {});
    ASSERT_GE(own.bundle.clefs.size(), 2u);
    const auto found =
        find_score_to_play(registry, "delete-folder", PlayOptions{.clef = "erm-phone"});
    const Clef erm = registry.clef("erm-phone");
    ASSERT_EQ(found.bundle.clefs.size(), own.bundle.clefs.size());
    for (const auto& [id, clef] : found.bundle.clefs) {
        EXPECT_EQ(clef.tempo, erm.tempo) << id;
        EXPECT_EQ(clef.type, erm.type) << id;
    }
}

TEST(PlayOptions, ClefDocumentsComeAsADictionaryOfStrings) {
    const std::map<std::string, std::string> clefs{{"my.clef.xml", "<VibClef/>"}};
    EXPECT_EQ(parse_play_options({{"clefs", sdbus::Variant(clefs)}}).clef_documents, clefs);
    EXPECT_THAT(invalid_options({{"clefs", sdbus::Variant(std::string("x"))}}),
                HasSubstr("option \"clefs\" must be a dictionary of strings (a{ss}), not s"));
}

TEST_F(ScoreToPlayTest, AClefSentAlongWithAnInlineScoreIsUsedUnderItsHrefEvenAPath) {
    PlayOptions options;
    options.clef_documents["clefs/mine.clef.xml"] = vibscore::testing::sine_clef(
        0.5, {60, 80, 100, 120, 140, 160}, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9});
    std::string score = inline_score();
    score.replace(score.find("lra-phone.clef.xml"), 18, "clefs/mine.clef.xml");
    const auto found = find_score_to_play(registry, score, options);
    EXPECT_EQ(found.bundle.clefs.at("lra").tempo, 0.5);
}

TEST_F(ScoreToPlayTest, AClefDocumentNoHrefNamesOrSentWithARegistryScoreIsRefused) {
    PlayOptions options;
    options.clef_documents["other.clef.xml"] = vibscore::testing::sine_clef(
        0.5, {60, 80, 100, 120, 140, 160}, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9});
    try {
        find_score_to_play(registry, inline_score(), options);
        ADD_FAILURE() << "no error";
    } catch (const RegistryError& error) {
        EXPECT_EQ(error.code(), RegistryError::Code::invalid_document);
        EXPECT_THAT(error.what(), HasSubstr("\"other.clef.xml\" is not named by any"));
    }
    EXPECT_THAT(refusal(RequestError::Code::invalid,
                        [&] { find_score_to_play(registry, "ringtone", options); }),
                HasSubstr("option \"clefs\" goes with an inline score"));
}

TEST_F(ScoreToPlayTest, AnInvalidClefSentAlongIsAnInvalidDocumentNamingItsHref) {
    PlayOptions options;
    options.clef_documents["lra-phone.clef.xml"] = "<VibClef type=\"sine\"";
    try {
        find_score_to_play(registry, inline_score(), options);
        ADD_FAILURE() << "no error";
    } catch (const RegistryError& error) {
        EXPECT_EQ(error.code(), RegistryError::Code::invalid_document);
        EXPECT_THAT(error.what(), HasSubstr("<inline clef \"lra-phone.clef.xml\">"));
    }
}

TEST_F(ScoreToPlayTest, TheRequestHoldsTheScoresCuesAndTheCallersChoices) {
    const auto score = find_score_to_play(registry, "ringtone", {});
    PlayOptions options;
    options.usage = Usage::ringtone;
    options.repeat = -1;
    options.intensity = 0.5;
    const PlaybackRequest request = make_playback_request(score, options, 0.030);

    render::RenderOptions render_options;
    render_options.separation_s = 0.030;
    const render::Performance performance(score.bundle, render_options);
    const auto expected = render::cue_schedule(performance);
    const auto cues = cues_of(request);
    ASSERT_EQ(cues.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(cues[i].at, expected[i].at) << i;
        EXPECT_EQ(cues[i].amplitude, expected[i].amplitude) << i;
    }
    EXPECT_EQ(request.duration_s, performance.duration());
    EXPECT_EQ(request.label, "ringtone");
    EXPECT_EQ(request.usage, Usage::ringtone);
    EXPECT_EQ(request.repeat, -1);
    EXPECT_EQ(request.intensity, 0.5);
}

TEST_F(ScoreToPlayTest, TheStartBarSkipsEarlierBarsAndTimeStartsThere) {
    const auto score = find_score_to_play(registry, inline_score(), {});
    PlayOptions options;
    options.start_bar = 1;
    const PlaybackRequest from_bar_1 = make_playback_request(score, options, 0.030);
    const PlaybackRequest whole = make_playback_request(score, {}, 0.030);
    const double tempo = registry.clef("lra-phone").tempo;
    EXPECT_NEAR(whole.duration_s, 4 * tempo, 1e-9);
    EXPECT_NEAR(from_bar_1.duration_s, 2 * tempo, 1e-9);
    const auto cues = cues_of(from_bar_1);
    const auto first_position = std::find_if(cues.begin(), cues.end(), [](const render::Cue& cue) {
        return cue.kind == render::Cue::Kind::position;
    });
    ASSERT_NE(first_position, cues.end());
    EXPECT_EQ(first_position->at, 0.0);
    EXPECT_EQ(first_position->bar, 1u);
    EXPECT_EQ(first_position->symbol, 0u);
}

TEST_F(ScoreToPlayTest, AStartBarPastTheLastBarIsOutOfRangeWithTheBarCount) {
    const auto score = find_score_to_play(registry, inline_score(), {});
    PlayOptions options;
    options.start_bar = 1;
    EXPECT_NO_THROW(make_playback_request(score, options, 0.030));
    options.start_bar = 2;
    EXPECT_EQ(refusal(RequestError::Code::out_of_range,
                      [&] { make_playback_request(score, options, 0.030); }),
              "start-bar 2 is past the last bar (the score has 2)");
}

TEST_F(ScoreToPlayTest, TheSeparationCutsTheEndOfANoteFollowedByAnother) {
    const auto score = find_score_to_play(registry, inline_score(), {});
    const auto first_off = [](const PlaybackRequest& request) {
        for (const auto& cue : cues_of(request)) {
            if (cue.kind == render::Cue::Kind::drive && cue.amplitude == 0.0) {
                return cue.at;
            }
        }
        return -1.0;
    };
    const double tempo = registry.clef("lra-phone").tempo;
    EXPECT_NEAR(first_off(make_playback_request(score, {}, 0.030)), tempo - 0.030, 1e-9);
    EXPECT_NEAR(first_off(make_playback_request(score, {}, 0.010)), tempo - 0.010, 1e-9);
}

}  // namespace
}  // namespace vibscore::daemon
