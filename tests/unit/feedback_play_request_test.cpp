// What vibscore-feedback asks vibscored's Play for (feedback/play_request.hpp): a registry
// score by name at its intensity times the maximum strength, a vibra feedback as the pattern
// feedbackd plays written on the pattern clef, capped at the maximum.
#include <gtest/gtest.h>

#include <filesystem>

#include "feedback/play_request.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore::feedback {
namespace {

const Clef& pattern_ms_clef() {
    static const Clef clef = load_clef_file(
        std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / kPatternClefHref);
    return clef;
}

// A clef getter that fails the test when it is asked.
const Clef& unexpected_clef() {
    ADD_FAILURE() << "the pattern clef was asked for";
    return pattern_ms_clef();
}

PlayRequest request(ThemeEntry entry, double max_strength = 1.0, int repeat = 0) {
    return {std::move(entry), "title", repeat, max_strength};
}

TEST(APlayRequest, PlaysARegistryScoreByNameAtItsIntensityTimesTheMaximumStrength) {
    ThemeEntry entry;
    entry.score = "ringtone";
    entry.usage = "ringtone";
    entry.intensity = 0.8;
    entry.clef = "erm-phone";
    const auto play = score_play(request(entry, 0.5, -1), unexpected_clef);
    ASSERT_TRUE(play);
    EXPECT_EQ(play->score, "ringtone");
    EXPECT_EQ(play->clef, "erm-phone");
    EXPECT_EQ(play->usage, "ringtone");
    EXPECT_EQ(play->repeat, -1);
    EXPECT_DOUBLE_EQ(play->intensity, 0.4);
    EXPECT_DOUBLE_EQ(score_play(request(entry), unexpected_clef)->intensity, 0.8);
}

TEST(APlayRequest, PlaysAVibraFeedbackAsItsPatternOnThePatternClefCappedAtTheMaximum) {
    ThemeEntry entry;
    entry.vibra = rumble_feedback(500, 2, 100, 0.8);  // message-new-sms at 0.8
    entry.usage = "notification";
    const auto full = score_play(request(entry), pattern_ms_clef);
    ASSERT_TRUE(full);
    EXPECT_EQ(full->clef, "");
    EXPECT_DOUBLE_EQ(full->intensity, 0.8);  // the strongest step, for the player to scale by
    const auto score = read_score(full->score, "t.score.xml").score;
    EXPECT_EQ(score.title, "title");
    ASSERT_EQ(score.clefs.size(), 1u);
    EXPECT_EQ(score.clefs[0].href, kPatternClefHref);
    const auto capped = score_play(request(entry, 0.3), pattern_ms_clef);
    EXPECT_DOUBLE_EQ(capped->intensity, 0.3);
    EXPECT_EQ(capped->score, full->score);  // the same shape, the same relations
}

TEST(APlayRequest, IsNothingForAVibraOfNoLengthOrAnEntryWithNothing) {
    ThemeEntry entry;
    entry.vibra = pattern_feedback({{1.0, 0}});
    EXPECT_FALSE(score_play(request(entry), unexpected_clef));
    EXPECT_FALSE(score_play(request(ThemeEntry{}), unexpected_clef));
}

}  // namespace
}  // namespace vibscore::feedback
