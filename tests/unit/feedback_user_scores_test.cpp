// The user's own score per event: its file (read, stored, kept when it does not read, its
// names at their limits) and how the event table plays it.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <stdexcept>

#include "feedback/event_table.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/user_scores.hpp"
#include "tests/fakes/fake_feedback_haptics.hpp"
#include "tests/support/support.hpp"

namespace vibscore::feedback {
namespace {

unsigned mode_of(const std::filesystem::path& path) {
    struct stat status {};
    ::stat(path.c_str(), &status);
    return status.st_mode & 07777;
}

UserScores read(const std::filesystem::path& file) {
    std::vector<Diagnostic> warnings;
    return read_user_scores(file, warnings);
}

TEST(UserScoresFile, IsEmptyWhenItDoesNotExist) {
    testing::TempDir dir;
    EXPECT_TRUE(read(dir.path() / "vibscore/feedback.json").empty());
}

TEST(UserScoresFile, IsMadeInAPrivateDirectoryAndReadsBack) {
    testing::TempDir dir;
    const auto file = dir.path() / "config/vibscore/feedback.json";
    store_user_score(file, "phone-incoming-call", "my-ring");
    store_user_score(file, "message-new-sms", "confirm");
    EXPECT_EQ(read(file),
              (UserScores{{"message-new-sms", "confirm"}, {"phone-incoming-call", "my-ring"}}));
    EXPECT_EQ(mode_of(file.parent_path()), 0700u);
    EXPECT_EQ(mode_of(file), 0600u);
    EXPECT_EQ(testing::read_file(file),
              "{\n  \"events\": {\n    \"phone-incoming-call\": \"my-ring\",\n"
              "    \"message-new-sms\": \"confirm\"\n  }\n}\n");
    store_user_score(file, "phone-incoming-call", "");
    EXPECT_EQ(read(file), (UserScores{{"message-new-sms", "confirm"}}));
    // Taking back a choice never made makes no file.
    store_user_score(dir.path() / "other/feedback.json", "a", "");
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "other"));
}

TEST(UserScoresFile, KeepsWhatElseItHoldsAndWarnsOfIt) {
    testing::TempDir dir;
    const auto file =
        dir.write("feedback.json", R"({"comment": "mine", "future": [1, 2.5, true, null],
 "events": {"a": "b"}})");
    std::vector<Diagnostic> warnings;
    EXPECT_EQ(read_user_scores(file, warnings), (UserScores{{"a", "b"}}));
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(format(warnings[0]), file.string() + ":1:2: unknown member \"comment\" ignored");
    store_user_score(file, "c", "d");
    EXPECT_EQ(testing::read_file(file),
              "{\n  \"comment\": \"mine\",\n  \"future\": [\n    1,\n    2.5,\n    true,\n"
              "    null\n  ],\n  \"events\": {\n    \"a\": \"b\",\n    \"c\": \"d\"\n  }\n}\n");
}

TEST(UserScoresFile, ThatDoesNotReadIsAnErrorAtItsPlaceAndIsNeverOverwritten) {
    testing::TempDir dir;
    const auto broken = dir.write("broken.json", "{\"events\": {\"a\": \"b\",}}");
    EXPECT_EQ(testing::first_diagnostic([&] { read(broken); }).where.column, 22);
    EXPECT_THROW(store_user_score(broken, "c", "d"), DocumentError);
    EXPECT_EQ(testing::read_file(broken), "{\"events\": {\"a\": \"b\",}}");
    const auto wrong = dir.write("wrong.json", "{\"events\": {\"a\": 3, \"B\": \"c\"}}");
    EXPECT_EQ(format(testing::first_diagnostic([&] { read(wrong); })),
              wrong.string() + ":1:18: expected a string, found 3");
    const auto name = dir.write("name.json", "{\"events\": {\"B\": \"c\"}}");
    EXPECT_EQ(format(testing::first_diagnostic([&] { read(name); })),
              name.string() +
                  ":1:13: event \"B\" is not an event name (a name is 1 to 64 of a-z 0-9 . _ -, "
                  "starting with a letter or a digit)");
}

TEST(UserScoresFile, TakesNamesOfSixtyFourCharactersAndRefusesSixtyFive) {
    testing::TempDir dir;
    const auto file = dir.path() / "feedback.json";
    const std::string longest(64, 'e');
    store_user_score(file, longest, std::string(64, 's'));
    EXPECT_EQ(read(file).at(longest), std::string(64, 's'));
    EXPECT_THROW(store_user_score(file, std::string(65, 'e'), "s"), std::invalid_argument);
    EXPECT_THROW(store_user_score(file, "e", std::string(65, 's')), std::invalid_argument);
    EXPECT_THROW(check_event_and_score("", "s"), std::invalid_argument);
    EXPECT_THROW(check_event_and_score("e", "-s"), std::invalid_argument);
    EXPECT_NO_THROW(check_event_and_score("e", ""));
}

TEST(UserScoresFile, IsInTheXdgConfigDirectoryElseInHomesDotConfig) {
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const std::string saved = config != nullptr ? config : "";
    ::setenv("XDG_CONFIG_HOME", "/tmp/x", 1);
    EXPECT_EQ(user_scores_path(), "/tmp/x/vibscore/feedback.json");
    ::setenv("XDG_CONFIG_HOME", "relative", 1);  // not absolute: ignored, as the spec says
    ::setenv("HOME", "/home/u", 1);
    EXPECT_EQ(user_scores_path(), "/home/u/.config/vibscore/feedback.json");
    if (config != nullptr) {
        ::setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
    } else {
        ::unsetenv("XDG_CONFIG_HOME");
    }
}

// -- In the event table ----------------------------------------------------------------------

class AnEventTableWithUserScores : public ::testing::Test {
  protected:
    AnEventTableWithUserScores()
        : table(haptics, theme(), {},
                {[this](std::uint32_t id, std::uint32_t reason) { ended.emplace_back(id, reason); },
                 nullptr}) {}
    static Theme theme() {
        Theme theme;
        ThemeEntry ring;
        ring.score = "ringtone";
        ring.usage = "ringtone";
        ring.intensity = 0.7;
        theme.add(Profile::quiet, "phone-incoming-call", ring);
        ThemeEntry click;
        click.score = "touch-click";
        click.usage = "touch";
        theme.add(Profile::full, "button-pressed", click);
        theme.add(Profile::quiet, "message-new-sms",
                  vibra_entry("message-new-sms", rumble_feedback(500, 2, 100)));
        return theme;
    }
    std::uint32_t trigger(const std::string& event) {
        const auto id = table.new_id();
        table.trigger(id, {":1.7", "a", event, std::nullopt, false, -1}, 0);
        return id;
    }

    testing::FakeFeedbackHaptics haptics;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ended;
    EventTable table;
};

TEST_F(AnEventTableWithUserScores, PlaysTheUsersScoreWithTheThemesUsageAtTheThemesLevel) {
    EXPECT_TRUE(table.set_user_scores({{"phone-incoming-call", "my-ring"}}));
    EXPECT_FALSE(table.set_user_scores({{"phone-incoming-call", "my-ring"}}));
    trigger("phone-incoming-call");
    ASSERT_EQ(haptics.requests.size(), 1u);
    EXPECT_EQ(haptics.requests[0].entry.score, "my-ring");
    EXPECT_EQ(haptics.requests[0].entry.usage, "ringtone");
    EXPECT_EQ(haptics.requests[0].entry.intensity, 1.0);  // the theme's was for its own score
    // button-pressed is a full-level event: in quiet the user's score gives nothing either.
    table.set_user_scores({{"button-pressed", "tick"}});
    table.set_profile(Profile::quiet);
    const auto id = trigger("button-pressed");
    EXPECT_EQ(ended.back(), std::pair(id, end_reason::not_found));
    table.set_profile(Profile::silent);
    table.set_user_scores({{"phone-incoming-call", "my-ring"}});
    EXPECT_EQ(trigger("phone-incoming-call"), 3u);
    EXPECT_EQ(haptics.requests.size(), 1u);
}

TEST_F(AnEventTableWithUserScores, PlaysAnEventTheThemeLacksAtQuietWithTheUsageOfItsName) {
    table.set_user_scores({{"alarm-clock-elapsed", "wake-up"}});
    trigger("alarm-clock-elapsed");
    ASSERT_EQ(haptics.requests.size(), 1u);
    EXPECT_EQ(haptics.requests[0].entry.usage, "alarm");
    table.playback_finished(haptics.next_playback - 1);
    table.set_profile(Profile::silent);
    const auto id = trigger("alarm-clock-elapsed");
    EXPECT_EQ(ended.back(), std::pair(id, end_reason::not_found));
    // Its level is quiet: switching to silent ends it.
    table.set_profile(Profile::quiet);
    trigger("alarm-clock-elapsed");
    table.set_profile(Profile::silent);
    EXPECT_EQ(haptics.stops.size(), 1u);
}

TEST_F(AnEventTableWithUserScores, PlaysTheThemesScoreWhenVibscoredHasNotTheUsers) {
    haptics.unknown_scores = {"gone", "nowhere"};
    table.set_user_scores({{"phone-incoming-call", "gone"}, {"window-close", "nowhere"}});
    trigger("phone-incoming-call");
    ASSERT_EQ(haptics.requests.size(), 2u);
    EXPECT_EQ(haptics.requests[1].entry.score, "ringtone");
    EXPECT_EQ(haptics.requests[1].entry.intensity, 0.7);
    EXPECT_EQ(table.playing(), 1u);
    // With no theme entry to fall back on, it gives no feedback.
    const auto id = trigger("window-close");
    EXPECT_EQ(ended.back(), std::pair(id, end_reason::not_found));
}

TEST_F(AnEventTableWithUserScores, ListsTheThemesEventsAndTheUsersInOrder) {
    table.set_user_scores({{"phone-incoming-call", "my-ring"}, {"alarm-clock-elapsed", "wake"}});
    EXPECT_EQ(table.event_scores(),
              (std::vector<EventScore>{{"alarm-clock-elapsed", "wake", "", true},
                                       {"button-pressed", "touch-click", "touch-click", false},
                                       {"message-new-sms", "", "", false},
                                       {"phone-incoming-call", "my-ring", "ringtone", true}}));
}

}  // namespace
}  // namespace vibscore::feedback
