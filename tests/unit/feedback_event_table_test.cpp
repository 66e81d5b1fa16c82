// The feedbackd API's rules without a bus (feedback/event_table.hpp), against a fake vibscored:
// levels, important events, ids and who may end them, timeouts at their edges, end reasons,
// profile changes, clients and vibscored leaving, and Haptic.Vibrate's limits.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "feedback/event_table.hpp"
#include "tests/fakes/fake_feedback_haptics.hpp"

namespace vibscore::feedback {
namespace {

constexpr std::uint64_t kSecond = 1'000'000;

ThemeEntry score_entry(const std::string& score, const std::string& usage) {
    ThemeEntry entry;
    entry.score = score;
    entry.usage = usage;
    return entry;
}

// ringtone and sms are quiet events (they play in full too), click is full only.
Theme test_theme() {
    Theme theme;
    theme.name = "test";
    theme.add(Profile::quiet, "phone-incoming-call", score_entry("ringtone", "ringtone"));
    theme.add(Profile::quiet, "message-new-sms", score_entry("message-new-sms", "notification"));
    theme.add(Profile::full, "button-pressed", score_entry("touch-click", "touch"));
    return theme;
}

struct Ended {
    std::uint32_t id;
    std::uint32_t reason;
    bool operator==(const Ended&) const = default;
};

class AnEventTable : public ::testing::Test {
  protected:
    explicit AnEventTable(FeedbackSettings settings = {})
        : table(haptics, test_theme(), std::move(settings),
                {[this](std::uint32_t id, std::uint32_t reason) {
                     ended.push_back({id, reason});
                 },
                 [this](std::optional<std::uint64_t> at) { deadlines.push_back(at); }}) {}

    // TriggerFeedback from `sender` at time `now`; the id the caller got.
    std::uint32_t trigger(const std::string& event, std::int32_t timeout = -1,
                          const std::string& sender = ":1.7",
                          std::optional<Profile> hint = std::nullopt, bool important = false,
                          const std::string& app_id = "org.example.App",
                          std::uint64_t now = 10 * kSecond) {
        const auto id = table.new_id();
        table.trigger(id, {sender, app_id, event, hint, important, timeout}, now);
        return id;
    }
    std::uint64_t last_playback() const { return haptics.next_playback - 1; }

    testing::FakeFeedbackHaptics haptics;
    std::vector<Ended> ended;
    std::vector<std::optional<std::uint64_t>> deadlines;
    EventTable table;
};

TEST_F(AnEventTable, PlaysAnEventsThemeEntryOnceAndEndsItNaturallyWhenItsPlaybackEnds) {
    const auto id = trigger("message-new-sms");
    EXPECT_EQ(id, 1u);
    ASSERT_EQ(haptics.requests.size(), 1u);
    EXPECT_EQ(haptics.requests[0].entry.score, "message-new-sms");
    EXPECT_EQ(haptics.requests[0].entry.usage, "notification");
    EXPECT_EQ(haptics.requests[0].repeat, 0);
    EXPECT_EQ(haptics.requests[0].title, "message-new-sms");
    EXPECT_EQ(table.playing(), 1u);
    EXPECT_TRUE(ended.empty());
    table.playback_finished(last_playback());
    EXPECT_EQ(ended, (std::vector<Ended>{{id, end_reason::natural}}));
    EXPECT_EQ(table.playing(), 0u);
    // Another playback's end is none of its business.
    table.playback_finished(4711);
    EXPECT_EQ(ended.size(), 1u);
}

TEST_F(AnEventTable, GivesIdsInOrderFromOne) {
    EXPECT_EQ(trigger("message-new-sms"), 1u);
    EXPECT_EQ(trigger("no-such-event"), 2u);
    EXPECT_EQ(trigger("message-new-sms"), 3u);
}

TEST_F(AnEventTable, EndsAnEventWithoutFeedbackAtOnceWithNotFound) {
    const auto unknown = trigger("no-such-event");
    EXPECT_EQ(ended, (std::vector<Ended>{{unknown, end_reason::not_found}}));
    EXPECT_TRUE(haptics.requests.empty());
    // vibscored refusing (Busy, or not there) is no feedback either, as feedbackd's busy vibra.
    haptics.refuse = true;
    const auto refused = trigger("message-new-sms");
    EXPECT_EQ(ended.back(), (Ended{refused, end_reason::not_found}));
    EXPECT_EQ(table.playing(), 0u);
}

TEST_F(AnEventTable, RepeatsAnEventWithATimeoutOfZeroOrMoreAndPlaysOneOfMinusOneOnce) {
    trigger("message-new-sms", -1);
    trigger("message-new-sms", 0);
    trigger("message-new-sms", 3);
    EXPECT_EQ(haptics.requests[0].repeat, 0);
    EXPECT_EQ(haptics.requests[1].repeat, -1);
    EXPECT_EQ(haptics.requests[2].repeat, -1);
}

TEST_F(AnEventTable, EndsAnEventWhoseTimeoutRunsOutWithExpiredAtItsDeadlineAndNotBefore) {
    const auto id =
        trigger("phone-incoming-call", 2, ":1.7", std::nullopt, false, "a", 5 * kSecond);
    const std::uint64_t deadline = 7 * kSecond;
    EXPECT_EQ(deadlines, (std::vector<std::optional<std::uint64_t>>{deadline}));
    table.expire(deadline - 1);
    EXPECT_TRUE(haptics.stops.empty());
    EXPECT_EQ(deadlines.back(), deadline);  // armed again for the same time
    table.expire(deadline);
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{last_playback()}));
    EXPECT_EQ(deadlines.back(), std::nullopt);
    EXPECT_TRUE(ended.empty());  // until vibscored reports the end
    table.playback_finished(last_playback());
    EXPECT_EQ(ended, (std::vector<Ended>{{id, end_reason::expired}}));
}

TEST_F(AnEventTable, ArmsTheEarliestTimeoutOfAllItsEvents) {
    trigger("message-new-sms", 5, ":1.7", std::nullopt, false, "a", 0);
    const auto soon = trigger("message-new-sms", 1, ":1.7", std::nullopt, false, "a", 0);
    trigger("message-new-sms", 0, ":1.7", std::nullopt, false, "a", 0);  // no timeout
    EXPECT_EQ(deadlines, (std::vector<std::optional<std::uint64_t>>{5 * kSecond, 1 * kSecond}));
    table.expire(1 * kSecond);
    table.playback_finished(haptics.stops.at(0));
    EXPECT_EQ(ended, (std::vector<Ended>{{soon, end_reason::expired}}));
    EXPECT_EQ(deadlines.back(), 5 * kSecond);
}

TEST_F(AnEventTable, LetsOnlyTheCallerEndItsOwnEvent) {
    const auto id = trigger("phone-incoming-call", 0, ":1.7");
    table.end(id, ":1.8");  // another client: ignored
    EXPECT_TRUE(haptics.stops.empty());
    table.end(id, ":1.7");
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{last_playback()}));
    table.end(id, ":1.7");  // already ending: asked once
    EXPECT_EQ(haptics.stops.size(), 1u);
    table.playback_finished(last_playback());
    EXPECT_EQ(ended, (std::vector<Ended>{{id, end_reason::explicit_end}}));
    table.end(id, ":1.7");  // over: ignored, as feedbackd ignores it
    table.end(9999, ":1.7");
    EXPECT_EQ(ended.size(), 1u);
    EXPECT_EQ(haptics.stops.size(), 1u);
}

TEST_F(AnEventTable, EndsAnEventAtOnceWhenVibscoredCannotStopItsPlayback) {
    const auto id = trigger("phone-incoming-call", 0);
    haptics.stop_works = false;
    table.end(id, ":1.7");
    EXPECT_EQ(ended, (std::vector<Ended>{{id, end_reason::explicit_end}}));
    EXPECT_EQ(table.playing(), 0u);
}

TEST_F(AnEventTable, EndsTheEventsAndPatternOfAClientThatLeavesTheBusAndNoOneElses) {
    const auto mine = trigger("phone-incoming-call", 0, ":1.7");
    const auto mine_playback = last_playback();
    const auto theirs = trigger("phone-incoming-call", 0, ":1.8");
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    const auto my_pattern = last_playback();
    ASSERT_TRUE(table.vibrate(":1.8", "b", {{1.0, 100}}));
    table.sender_left(":1.7");
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{mine_playback, my_pattern}));
    table.playback_finished(mine_playback);
    EXPECT_EQ(ended, (std::vector<Ended>{{mine, end_reason::explicit_end}}));
    EXPECT_EQ(table.playing(), 1u);
    (void)theirs;
}

TEST_F(AnEventTable, EndsEveryEventWhenVibscoredLeavesTheBus) {
    const auto playing = trigger("phone-incoming-call", 0);
    const auto ending = trigger("message-new-sms", 0);
    table.end(ending, ":1.7");
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    const auto stops = haptics.stops.size();
    table.haptics_gone();
    // Each with the reason it had: nothing asked, natural; the one being ended, explicit.
    EXPECT_EQ(ended, (std::vector<Ended>{{playing, end_reason::natural},
                                         {ending, end_reason::explicit_end}}));
    EXPECT_EQ(table.playing(), 0u);
    // Its pattern is forgotten: a later pattern does not ask the vanished playback to stop.
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    EXPECT_EQ(haptics.stops.size(), stops);
}

TEST_F(AnEventTable, SwitchedToSilentEndsItsEventsAndStopsARunningPattern) {
    const auto quiet_event = trigger("message-new-sms", 0);
    const auto event_playback = last_playback();
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 5000}}));
    const auto pattern = last_playback();
    EXPECT_TRUE(table.set_profile(Profile::silent));
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{event_playback, pattern}));
    table.playback_finished(event_playback);
    EXPECT_EQ(ended, (std::vector<Ended>{{quiet_event, end_reason::explicit_end}}));
    EXPECT_FALSE(table.set_profile(Profile::silent));  // no change
}

TEST_F(AnEventTable, SwitchedToQuietEndsOnlyFeedbackOfTheFullLevelAndKeepsPatterns) {
    const auto full_event = trigger("button-pressed", 0);
    const auto full_playback = last_playback();
    trigger("message-new-sms", 0);
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 5000}}));
    EXPECT_TRUE(table.set_profile(Profile::quiet));
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{full_playback}));
    table.playback_finished(full_playback);
    EXPECT_EQ(ended, (std::vector<Ended>{{full_event, end_reason::explicit_end}}));
    // In quiet, a full-only event gives nothing; a quiet one plays.
    const auto click = trigger("button-pressed");
    EXPECT_EQ(ended.back(), (Ended{click, end_reason::not_found}));
    EXPECT_EQ(table.profile(), Profile::quiet);
}

TEST_F(AnEventTable, LowersTheLevelForAProfileHintButNeverRaisesIt) {
    const auto hinted = trigger("message-new-sms", -1, ":1.7", Profile::silent);
    EXPECT_EQ(ended.back(), (Ended{hinted, end_reason::not_found}));
    table.set_profile(Profile::quiet);
    const auto raised = trigger("button-pressed", -1, ":1.7", Profile::full);
    EXPECT_EQ(ended.back(), (Ended{raised, end_reason::not_found}));
}

class AnEventTableInSilent : public AnEventTable {
  protected:
    AnEventTableInSilent() : AnEventTable({.profile = Profile::silent}) {}
};

TEST_F(AnEventTableInSilent, PlaysAnImportantEventOfAnAllowedAppAtFullAsFeedbackd08Does) {
    // feedbackd 0.8.2's allow-important default.
    EXPECT_EQ(table.settings().allow_important,
              (std::vector<std::string>{"org.sigxcpu.FbdAlertSlider", "org.gnome.clocks"}));
    const auto alarm =
        trigger("button-pressed", -1, ":1.7", std::nullopt, true, "org.gnome.clocks");
    EXPECT_TRUE(ended.empty());
    EXPECT_EQ(haptics.requests.size(), 1u);
    // Its profile hint still chooses the level.
    const auto hinted =
        trigger("button-pressed", -1, ":1.7", Profile::quiet, true, "org.gnome.clocks");
    EXPECT_EQ(ended.back(), (Ended{hinted, end_reason::not_found}));
    const auto quiet =
        trigger("message-new-sms", -1, ":1.7", Profile::quiet, true, "org.sigxcpu.FbdAlertSlider");
    EXPECT_EQ(haptics.requests.back().entry.score, "message-new-sms");
    (void)alarm;
    (void)quiet;
}

TEST_F(AnEventTableInSilent, IgnoresTheImportantHintOfAnAppNotAllowedAndImportantFalse) {
    const auto stranger =
        trigger("message-new-sms", -1, ":1.7", std::nullopt, true, "org.example.Spam");
    EXPECT_EQ(ended.back(), (Ended{stranger, end_reason::not_found}));
    const auto not_important =
        trigger("message-new-sms", -1, ":1.7", std::nullopt, false, "org.gnome.clocks");
    EXPECT_EQ(ended.back(), (Ended{not_important, end_reason::not_found}));
    // A prefix or a different case is another app.
    trigger("message-new-sms", -1, ":1.7", std::nullopt, true, "org.gnome.clock");
    trigger("message-new-sms", -1, ":1.7", std::nullopt, true, "org.gnome.Clocks");
    EXPECT_TRUE(haptics.requests.empty());
    table.set_allow_important({"org.example.Spam"});
    trigger("message-new-sms", -1, ":1.7", std::nullopt, true, "org.example.Spam");
    EXPECT_EQ(haptics.requests.size(), 1u);
    table.set_allow_important({});
    trigger("message-new-sms", -1, ":1.7", std::nullopt, true, "org.gnome.clocks");
    EXPECT_EQ(haptics.requests.size(), 1u);
}

TEST_F(AnEventTableInSilent, EndsAnImportantEventWhenTheProfileDropsBelowItsThemeLevel) {
    trigger("message-new-sms", 0, ":1.7", std::nullopt, true, "org.gnome.clocks");
    // The sms entry is a quiet one: quiet keeps it, as feedbackd compares the theme's level.
    EXPECT_TRUE(table.set_profile(Profile::quiet));
    EXPECT_TRUE(haptics.stops.empty());
    EXPECT_TRUE(table.set_profile(Profile::silent));
    EXPECT_EQ(haptics.stops.size(), 1u);
}

TEST_F(AnEventTable, SendsTheMaximumHapticStrengthWithEveryRequest) {
    trigger("message-new-sms");
    EXPECT_EQ(haptics.requests.back().max_strength, 1.0);
    table.set_max_haptic_strength(0.4);
    trigger("message-new-sms");
    EXPECT_EQ(haptics.requests.back().max_strength, 0.4);
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    EXPECT_EQ(haptics.requests.back().max_strength, 0.4);
    table.set_max_haptic_strength(1.5);
    EXPECT_EQ(table.settings().max_haptic_strength, 1.0);
}

// -- Haptic.Vibrate ------------------------------------------------------------------------

std::vector<HapticStep> steps(std::size_t count, HapticStep step = {0.5, 10}) {
    return std::vector<HapticStep>(count, step);
}

TEST_F(AnEventTable, PlaysTenPatternStepsAndDropsAnEleventhAsFeedbackdDoes) {
    ASSERT_TRUE(table.vibrate(":1.7", "a", steps(10)));
    EXPECT_EQ(haptics.requests.back().entry.vibra->steps.size(), 10u);
    ASSERT_TRUE(table.vibrate(":1.7", "a", steps(11)));
    EXPECT_EQ(haptics.requests.back().entry.vibra->steps.size(), 10u);
    EXPECT_EQ(haptics.requests.back().entry.vibra->duration_ms, 100u);
    EXPECT_EQ(haptics.requests.back().entry.usage, "touch");
    EXPECT_EQ(haptics.requests.back().repeat, 0);
}

TEST_F(AnEventTable, KeepsAStepOfTenSecondsAndShortensOneMillisecondLonger) {
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 10'000}, {1.0, 10'001}, {1.0, 4'000'000'000}}));
    EXPECT_EQ(haptics.requests.back().entry.vibra->steps,
              (std::vector<VibraStep>{{1.0, 10'000}, {1.0, 10'000}, {1.0, 10'000}}));
}

TEST_F(AnEventTable, ClampsStrengthsOutsideZeroToOneAndRefusesOneThatIsNotANumber) {
    ASSERT_TRUE(table.vibrate(":1.7", "a",
                              {{1.0, 10}, {1.0000001, 10}, {-0.5, 10}, {HUGE_VAL, 10}, {0.0, 10}}));
    EXPECT_EQ(haptics.requests.back().entry.vibra->steps,
              (std::vector<VibraStep>{{1.0, 10}, {1.0, 10}, {0.0, 10}, {1.0, 10}, {0.0, 10}}));
    try {
        table.vibrate(":1.7", "a", {{0.5, 10}, {std::nan(""), 10}});
        FAIL() << "no error";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "step 2: the strength is not a number");
    }
}

TEST_F(AnEventTable, ReplacesOnlyTheCallersOwnPatternAndAnEmptyOneEndsIt) {
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 5000}}));
    const auto mine = last_playback();
    ASSERT_TRUE(table.vibrate(":1.8", "b", {{1.0, 5000}}));
    const auto theirs = last_playback();
    EXPECT_TRUE(haptics.stops.empty());
    ASSERT_TRUE(table.vibrate(":1.8", "b", {{0.5, 100}}));
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{theirs}));
    EXPECT_TRUE(table.vibrate(":1.8", "b", {}));  // empty: their new one ends, mine goes on
    EXPECT_EQ(haptics.stops, (std::vector<std::uint64_t>{theirs, last_playback()}));
    EXPECT_TRUE(table.vibrate(":1.7", "a", {{1.0, 0}}));  // 0 ms: as empty
    EXPECT_EQ(haptics.stops.back(), mine);
    const auto plays = haptics.requests.size();
    EXPECT_TRUE(table.vibrate(":1.7", "a", {}));  // nothing of mine left: nothing to stop
    EXPECT_EQ(haptics.stops.size(), 3u);
    EXPECT_EQ(haptics.requests.size(), plays);
}

TEST_F(AnEventTable, TitlesAPatternWithItsAppIdBoundedAndWithoutControlCharacters) {
    ASSERT_TRUE(table.vibrate(":1.7", std::string(1000, 'a') + "\n", {{1.0, 10}}));
    EXPECT_EQ(haptics.requests.back().title,
              "haptic pattern of \"" + std::string(80, 'a') + "\"... (1001 bytes)");
    ASSERT_TRUE(table.vibrate(":1.7", "org.example\nApp", {{1.0, 10}}));
    EXPECT_EQ(haptics.requests.back().title, "haptic pattern of \"org.example\\x0aApp\"");
}

TEST_F(AnEventTable, ForgetsAPatternVibscoredEnded) {
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    table.playback_finished(last_playback());
    ASSERT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    EXPECT_TRUE(haptics.stops.empty());
}

TEST_F(AnEventTable, VibratesInQuietButNotInSilentNorWhenVibscoredRefuses) {
    table.set_profile(Profile::quiet);
    EXPECT_TRUE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    table.set_profile(Profile::silent);
    const auto plays = haptics.requests.size();
    EXPECT_FALSE(table.vibrate(":1.7", "a", {{1.0, 100}}));
    EXPECT_EQ(haptics.requests.size(), plays);
    table.set_profile(Profile::full);
    haptics.refuse = true;
    EXPECT_FALSE(table.vibrate(":1.7", "a", {{1.0, 100}}));
}

TEST(AppIdList, ReadsTheIdsOfACommaSeparatedListInOrder) {
    EXPECT_EQ(parse_app_id_list("org.gnome.clocks"),
              (std::vector<std::string>{"org.gnome.clocks"}));
    EXPECT_EQ(parse_app_id_list("a,b,c"), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(AppIdList, EmptyItemsNameNoneSoAnEmptyListAllowsNone) {
    EXPECT_TRUE(parse_app_id_list("").empty());
    EXPECT_TRUE(parse_app_id_list(",").empty());
    EXPECT_TRUE(parse_app_id_list(",,").empty());
    EXPECT_EQ(parse_app_id_list(",a,,b,"), (std::vector<std::string>{"a", "b"}));
}

TEST(AppIdList, WritesBackWhatItReadsSoTheCommandLineDefaultIsTheSettingsDefault) {
    EXPECT_EQ(app_id_list({}), "");
    EXPECT_EQ(app_id_list({"a"}), "a");
    const auto defaults = FeedbackSettings().allow_important;
    EXPECT_EQ(app_id_list(defaults), "org.sigxcpu.FbdAlertSlider,org.gnome.clocks");
    EXPECT_EQ(parse_app_id_list(app_id_list(defaults)), defaults);
}

}  // namespace
}  // namespace vibscore::feedback
