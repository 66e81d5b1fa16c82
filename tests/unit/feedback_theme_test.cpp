// vibscore-feedback's themes: its own format, feedbackd's theme JSON (Debian's real default
// theme, not a copy), the lookup by profile, and errors that say where a file is wrong.
#include <gtest/gtest.h>

#include <filesystem>

#include "daemon/usage.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/theme.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::feedback {
namespace {

constexpr const char* kFeedbackdTheme = "/usr/share/feedbackd/themes/default.json";
constexpr double kRumble = 32768.0 / 65535.0;

std::string error_of(const std::string& text) {
    try {
        parse_theme(JsonDocument(text, "t.json"));
    } catch (const DocumentError& error) {
        return error.what();
    }
    return "<no error>";
}

std::string theme_with(const std::string& quiet_events) {
    return "{\"vibscore-theme\": 1, \"name\": \"t\",\n \"profiles\": {\"quiet\": {\n" +
           quiet_events + "\n}}}";
}

TEST(FeedbackdTheme, DebiansDefaultThemePlaysItsVibraEntriesAsFeedbackdWould) {
    const Theme theme = load_theme(kFeedbackdTheme);
    EXPECT_EQ(theme.name, "default");
    // message-new-sms: duration 500, count 2, pause 100: two rumbles of 150 ms.
    const auto* sms = theme.lookup("message-new-sms", Profile::quiet);
    ASSERT_NE(sms, nullptr);
    EXPECT_TRUE(sms->score.empty());
    EXPECT_EQ(sms->pattern, (VibrationPattern{{0.15, kRumble, kRumble, 0},
                                              {0.1, 0, 0, 0},
                                              {0.15, kRumble, kRumble, 0},
                                              {0.1, 0, 0, 0}}));
    EXPECT_EQ(sms->usage, "notification");
    // message-new-email: 750 ms in three: 150 ms rumbles, 100 ms apart.
    EXPECT_EQ(theme.lookup("message-new-email", Profile::quiet)->pattern.size(), 6u);
    EXPECT_EQ(theme.lookup("message-new-email", Profile::quiet)->pattern[0].seconds, 0.15);
    // button-pressed: one 15 ms rumble, a touch.
    const auto* button = theme.lookup("button-pressed", Profile::full);
    ASSERT_NE(button, nullptr);
    EXPECT_EQ(button->pattern, (VibrationPattern{{0.015, kRumble, kRumble, 0}}));
    EXPECT_EQ(button->usage, "touch");
    // alarm-clock-elapsed: fades in from 4096 to 32767 over its whole 10 s.
    const auto* alarm = theme.lookup("alarm-clock-elapsed", Profile::quiet);
    ASSERT_NE(alarm, nullptr);
    EXPECT_EQ(alarm->pattern, (VibrationPattern{{10.0, 4096.0 / 32767.0, 1.0, 0}}));
    EXPECT_EQ(alarm->usage, "alarm");
    // phone-incoming-call: 10 s at full strength, a ringtone.
    const auto* call = theme.lookup("phone-incoming-call", Profile::quiet);
    ASSERT_NE(call, nullptr);
    EXPECT_EQ(call->pattern, (VibrationPattern{{10.0, 1.0, 1.0, 0}}));
    EXPECT_EQ(call->usage, "ringtone");
}

TEST(FeedbackdTheme, SoundAndLedEntriesGiveNoVibrationAndSilentGivesNone) {
    const Theme theme = load_theme(kFeedbackdTheme);
    EXPECT_EQ(theme.lookup("camera-shutter", Profile::full), nullptr);     // Sound only
    EXPECT_EQ(theme.lookup("battery-caution", Profile::silent), nullptr);  // Led only
    EXPECT_EQ(theme.lookup("button-pressed", Profile::silent), nullptr);
    EXPECT_EQ(theme.lookup("no-such-event", Profile::full), nullptr);
}

TEST(FeedbackdTheme, ARumbleWithNoTimeLeftIsFeedbackdsOneSecondFallback) {
    EXPECT_EQ(rumble_pattern(100, 2, 50), (VibrationPattern{{1.0, kRumble, kRumble, 0}}));
    EXPECT_EQ(rumble_pattern(300, 3, 0), (VibrationPattern{{0.1, kRumble, kRumble, 0},
                                                           {0.1, kRumble, kRumble, 0},
                                                           {0.1, kRumble, kRumble, 0}}));
}

TEST(FeedbackdTheme, PeriodicDefaultsAreFullStrengthWithoutAFade) {
    EXPECT_EQ(periodic_pattern(500, 0, 0, 0), (VibrationPattern{{0.5, 1.0, 1.0, 0}}));
    EXPECT_EQ(periodic_pattern(500, 0x4000, 0x1000, 200),
              (VibrationPattern{{0.2, 0x1000 / 32767.0, 0x4000 / 32767.0, 0},
                                {0.3, 0x4000 / 32767.0, 0x4000 / 32767.0, 0}}));
}

TEST(VibscoreTheme, TheShippedThemeNamesShippedScoresForEveryEventFeedbackdVibratesFor) {
    const Theme shipped = load_theme(testing::required_env("VIBSCORE_FEEDBACK_THEME"));
    const auto clefs = std::filesystem::path(testing::required_env("VIBSCORE_CLEFS"));
    for (const auto& [event, levels] : shipped.events()) {
        for (const auto& [profile, entry] : levels) {
            EXPECT_TRUE(std::filesystem::exists(clefs / (entry.score + ".score.xml")))
                << event << ": " << entry.score;
            EXPECT_NO_THROW(load_score_file(clefs / (entry.score + ".score.xml"))) << event;
            EXPECT_TRUE(daemon::parse_usage(entry.usage)) << event;
        }
    }
    const Theme feedbackd = load_theme(kFeedbackdTheme);
    for (const auto& [event, levels] : feedbackd.events()) {
        for (const auto profile : {Profile::quiet, Profile::full}) {
            if (feedbackd.lookup(event, profile) != nullptr) {
                EXPECT_NE(shipped.lookup(event, profile), nullptr) << event;
            }
        }
    }
    EXPECT_EQ(shipped.lookup("button-pressed", Profile::silent), nullptr);
}

TEST(VibscoreTheme, AnEntryOfALowerProfilePlaysInTheHigherOnesUnlessTheyHaveTheirOwn) {
    const auto theme = parse_theme(JsonDocument(
        R"({"vibscore-theme": 1, "name": "t", "profiles": {
             "quiet": {"a": {"score": "alarm", "usage": "alarm"}, "b": {"score": "touch-tick"}},
             "full": {"a": {"score": "ringtone", "usage": "alarm", "intensity": 0.5,
                            "clef": "erm-phone"}}}})",
        "t.json"));
    EXPECT_EQ(theme.lookup("a", Profile::quiet)->score, "alarm");
    EXPECT_EQ(theme.lookup("a", Profile::full)->score, "ringtone");
    EXPECT_EQ(theme.lookup("a", Profile::full)->intensity, 0.5);
    EXPECT_EQ(theme.lookup("a", Profile::full)->clef, "erm-phone");
    EXPECT_EQ(theme.level_of("b", Profile::full), Profile::quiet);
    EXPECT_EQ(theme.lookup("b", Profile::full)->usage, "notification");  // by the event's name
    EXPECT_EQ(theme.lookup("a", Profile::silent), nullptr);
}

TEST(ThemeErrors, MalformedJsonNamesTheFileLineAndColumn) {
    EXPECT_EQ(error_of("{\n  \"name\": \"x\",\n  \"profiles\": [,]\n}"),
              "t.json:3:16: not JSON: syntax error while parsing value - unexpected ','; "
              "expected '[', '{', or a literal");
}

TEST(ThemeErrors, AWrongValueIsNamedWhereItStands) {
    EXPECT_EQ(error_of(theme_with("  \"e\": {\"score\": \"x\", \"usage\": \"loud\"}")),
              "t.json:3:32: unknown usage \"loud\" (expected ringtone, alarm, notification, "
              "communication, accessibility, hardware-feedback, touch, media)");
    EXPECT_EQ(error_of(theme_with("  \"e\": {\"score\": 7}")),
              "t.json:3:18: expected a string, found 7");
    EXPECT_EQ(error_of(theme_with("  \"e\": {\"score\": \"x\", \"volume\": 1}")),
              "t.json:3:23: unknown member \"volume\" (expected score, usage, intensity or clef)");
    EXPECT_EQ(error_of(theme_with("  \"e\": {\"usage\": \"touch\"}")),
              "t.json:3:8: missing \"score\"");
    EXPECT_EQ(error_of(theme_with("  \"e\": {\"score\": \"x\", \"intensity\": 1.5}")),
              "t.json:3:36: expected a number from 0 to 1, found 1.5");
    EXPECT_EQ(error_of(R"({"vibscore-theme": 1, "name": "t", "profiles": {"loud": {}}})"),
              "t.json:1:49: unknown profile \"loud\" (expected full, quiet or silent)");
    EXPECT_EQ(error_of(R"({"vibscore-theme": 2, "name": "t", "profiles": {}})"),
              "t.json:1:20: expected a whole number from 1 to 1, found 2");
}

TEST(ThemeErrors, FeedbackdThemesAreCheckedAsStrictly) {
    EXPECT_EQ(error_of(R"({"name": "t", "profiles": [{"name": "quiet", "feedbacks": [
        {"event-name": "e", "type": "VibraWobble"}]}]})"),
              "t.json:2:37: unknown feedback type \"VibraWobble\" (expected Sound, Led, Dummy, "
              "VibraRumble or VibraPeriodic)");
    EXPECT_EQ(error_of(R"({"name": "t", "profiles": [{"name": "quiet", "feedbacks": [
        {"event-name": "e", "type": "VibraRumble", "count": 0}]}]})"),
              "t.json:2:61: expected a whole number from 1 to 1000000, found 0");
    EXPECT_EQ(error_of(R"({"name": "t", "profiles": [{"name": "quiet", "feedbacks": [
        {"event-name": "e", "type": "VibraPeriodic", "magnitude": 40000}]}]})"),
              "t.json:2:67: expected a whole number from 0 to 32767, found 40000");
    EXPECT_EQ(error_of("[]"), "t.json:1:1: a theme is a JSON object");
}

TEST(ThemeErrors, AFileThatCannotBeReadSaysSo) {
    EXPECT_THROW(load_theme("/nonexistent/theme.json"), DocumentError);
    try {
        load_theme("/nonexistent/theme.json");
    } catch (const DocumentError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "/nonexistent/theme.json: cannot open: No such file or directory");
    }
}

TEST(EventUsage, FollowsTheEventNamingSpec) {
    EXPECT_EQ(usage_for_event("phone-incoming-call"), "ringtone");
    EXPECT_EQ(usage_for_event("alarm-clock-elapsed"), "alarm");
    EXPECT_EQ(usage_for_event("button-released"), "touch");
    EXPECT_EQ(usage_for_event("window-close"), "touch");
    EXPECT_EQ(usage_for_event("message-sent-instant"), "touch");
    EXPECT_EQ(usage_for_event("message-new-instant"), "notification");
    EXPECT_EQ(usage_for_event("bell-terminal"), "notification");
}

}  // namespace
}  // namespace vibscore::feedback
