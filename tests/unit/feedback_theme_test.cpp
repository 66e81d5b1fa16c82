// vibscore-feedback's themes: its own format; feedbackd's theme JSON read as feedbackd 0.8.2
// reads it, from fixtures these tests write (as feedbackd keeps its own in tests/data) and from
// each Debian release's default theme as it is shipped; parent themes merged as feedbackd
// merges them; the lookup by profile; and errors and warnings that say where a file is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/usage.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/theme.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::feedback {
namespace {

// Each release's feedbackd default theme, as its package installs it: the host's (Debian 12:
// feedbackd 0.0.3; in the trixie tier, Debian 13's 0.8.2) and the trixie chroot's when this
// machine has one.
const std::vector<std::string>& shipped_feedbackd_themes() {
    static const std::vector<std::string> themes = [] {
        std::vector<std::string> found;
        for (const char* path : {"/usr/share/feedbackd/themes/default.json",
                                 "/srv/trixie/usr/share/feedbackd/themes/default.json"}) {
            if (std::filesystem::exists(path)) {
                found.emplace_back(path);
            }
        }
        return found;
    }();
    return themes;
}

// A search that finds nothing unless a test puts it there.
ThemeSearch no_parents() {
    ThemeSearch search;
    search.builtin_dir = "/nonexistent/feedbackd/themes";
    return search;
}

Theme theme_from(const std::string& text, const ThemeSearch& search = no_parents()) {
    return parse_theme(JsonDocument(text, "t.json"), search);
}

std::string error_of(const std::string& text, const ThemeSearch& search = no_parents()) {
    try {
        theme_from(text, search);
    } catch (const DocumentError& error) {
        return error.what();
    }
    return "<no error>";
}

std::vector<std::string> warnings_of(const Theme& theme) {
    std::vector<std::string> texts;
    for (const auto& warning : theme.warnings) {
        texts.push_back(format(warning));
    }
    return texts;
}

// A feedbackd theme with these feedbacks in profile quiet.
std::string feedbackd_theme(const std::string& quiet_feedbacks, const std::string& more = "") {
    return "{\"name\": \"t\"," + more +
           "\n \"profiles\": [{\"name\": \"quiet\", \"feedbacks\": [\n" + quiet_feedbacks +
           "\n]}]}";
}

std::string vibscore_theme(const std::string& quiet_events) {
    return "{\"vibscore-theme\": 1, \"name\": \"t\",\n \"profiles\": {\"quiet\": {\n" +
           quiet_events + "\n}}}";
}

const VibraFeedback& vibra(const Theme& theme, const std::string& event,
                           Profile profile = Profile::quiet) {
    const ThemeEntry* entry = theme.lookup(event, profile);
    if (entry == nullptr || !entry->vibra) {
        throw std::runtime_error("no vibra feedback for " + event);
    }
    return *entry->vibra;
}

// -- Each release's default theme, as shipped ----------------------------------------------

TEST(FeedbackdsShippedTheme, LoadsAndGivesEveryVibraEntryOfItThePatternFeedbackdPlays) {
    if (shipped_feedbackd_themes().empty()) {
        GTEST_SKIP() << "no feedbackd default theme on this machine";
    }
    for (const auto& path : shipped_feedbackd_themes()) {
        SCOPED_TRACE(path);
        const Theme theme = load_theme(path, no_parents());
        EXPECT_EQ(theme.name, "default");
        // Walk the file itself: every vibra entry, by profile, has its feedback, whose pattern
        // lasts what the entry says.
        const JsonDocument document = read_json_file(path);
        std::size_t vibra_entries = 0;
        for (const auto& profile : document.root().find("profiles")->items) {
            const auto level = parse_profile(profile.find("name")->text);
            ASSERT_TRUE(level);
            for (const auto& entry : profile.find("feedbacks")->items) {
                if (!entry.find("type")->text.starts_with("Vibra")) {
                    continue;
                }
                ++vibra_entries;
                const std::string event = entry.find("event-name")->text;
                const auto& feedback = vibra(theme, event, *level);
                unsigned ms = 0;
                if (const auto* durations = entry.find("durations")) {
                    for (const auto& step : durations->items) {
                        ms += static_cast<unsigned>(step.number);
                    }
                } else {
                    ms = static_cast<unsigned>(entry.find("duration")->number);
                }
                EXPECT_EQ(feedback.duration_ms, ms) << event;
                EXPECT_NEAR(pattern_seconds(vibra_pattern(feedback)), ms / 1000.0, 1e-9) << event;
                EXPECT_GT(pattern_seconds(vibra_pattern(feedback)), 0.0) << event;
            }
        }
        EXPECT_GE(vibra_entries, 12u);
    }
}

TEST(FeedbackdsShippedTheme, OfDebian13PlaysItsPatternsAndFloatMagnitudesWithoutAWarning) {
    const std::string path = "/srv/trixie/usr/share/feedbackd/themes/default.json";
    const std::string here = "/usr/share/feedbackd/themes/default.json";
    // In the trixie tier the host's theme is Debian 13's.
    const bool trixie_here = std::filesystem::exists(here) &&
                             testing::read_file(here).find("VibraPattern") != std::string::npos;
    if (!std::filesystem::exists(path) && !trixie_here) {
        GTEST_SKIP() << "no feedbackd 0.8 theme on this machine";
    }
    const Theme theme = load_theme(trixie_here ? here : path, no_parents());
    EXPECT_EQ(warnings_of(theme), std::vector<std::string>{});
    EXPECT_EQ(vibra(theme, "notification-new-generic"),
              pattern_feedback({{0.25, 50}, {0.0, 250}, {0.25, 50}}));
    EXPECT_EQ(vibra(theme, "message-new-cellbroadcast"),
              pattern_feedback({{1.0, 200}, {0.0, 200}}));
    EXPECT_EQ(vibra(theme, "button-pressed"), pattern_feedback({{0.2, 7}}));
    // magnitude 0.5 over 1000 ms, fading in from 0 over feedbackd 0.8's default 500 ms.
    EXPECT_EQ(vibra(theme, "phone-incoming-call"), periodic_feedback(1000, 0.5, 0.0, 500));
    EXPECT_EQ(vibra(theme, "message-new-sms"), rumble_feedback(500, 2, 100));
    EXPECT_EQ(theme.lookup("message-new-sms", Profile::full)->vibra,
              vibra(theme, "message-new-sms"));
    EXPECT_EQ(theme.lookup("message-new-sms", Profile::silent), nullptr);
}

TEST(FeedbackdsShippedTheme, OfDebian12HasItsOldMagnitudesConvertedWithAWarningEach) {
    const std::string path = "/usr/share/feedbackd/themes/default.json";
    if (!std::filesystem::exists(path) ||
        testing::read_file(path).find("32767") == std::string::npos) {
        GTEST_SKIP() << "no feedbackd 0.0.3 theme on this machine";
    }
    const Theme theme = load_theme(path, no_parents());
    // alarm-clock-elapsed: magnitude 32767 and fade-in-level 4096 of 0.0.3's 0..32767.
    EXPECT_EQ(vibra(theme, "alarm-clock-elapsed"),
              periodic_feedback(10000, 1.0, 4096.0 / 32767.0, 10000));
    EXPECT_EQ(vibra(theme, "theme-demo"), periodic_feedback(5000, 1.0, 0.0, 500));
    ASSERT_EQ(theme.warnings.size(), 3u);
    EXPECT_EQ(theme.warnings[0].message,
              "magnitude 32767 is of feedbackd 0.0.3's scale (0 to 32767): read as 1 of full "
              "(feedbackd 0.8 divides by 65535); please update the theme");
    EXPECT_EQ(theme.warnings[0].where.file, path);
    EXPECT_GT(theme.warnings[0].where.line, 0);
}

// -- feedbackd 0.8's entries, from fixtures --------------------------------------------------

TEST(FeedbackdTheme, ReadsVibraPatternsAsStepsThatLastTheirSum) {
    const auto theme = theme_from(feedbackd_theme(
        R"({"event-name": "e", "type": "VibraPattern", "magnitudes": [1.0, 0, 0.3],
            "durations": [200, 100, 50]})"));
    EXPECT_EQ(vibra(theme, "e"), pattern_feedback({{1.0, 200}, {0.0, 100}, {0.3, 50}}));
    EXPECT_EQ(vibra(theme, "e").duration_ms, 350u);
    EXPECT_EQ(theme.lookup("e", Profile::quiet)->usage, "notification");
    EXPECT_TRUE(theme.warnings.empty());
}

TEST(FeedbackdTheme, ClampsPatternMagnitudesAndPlaysNothingForPatternsItCannotPlay) {
    const auto theme = theme_from(feedbackd_theme(
        R"({"event-name": "clamped", "type": "VibraPattern", "magnitudes": [1.5, -0.5],
            "durations": [10, 10]},
{"event-name": "uneven", "type": "VibraPattern", "magnitudes": [1, 1], "durations": [10]},
{"event-name": "half", "type": "VibraPattern", "magnitudes": [1]},
{"event-name": "long", "type": "VibraPattern", "magnitudes": [1], "durations": [10],
 "duration": 5000})"));
    EXPECT_EQ(vibra(theme, "clamped"), pattern_feedback({{1.0, 10}, {0.0, 10}}));
    EXPECT_EQ(theme.lookup("uneven", Profile::quiet), nullptr);
    EXPECT_EQ(theme.lookup("half", Profile::quiet), nullptr);
    EXPECT_EQ(vibra(theme, "long").duration_ms, 10u);
    EXPECT_EQ(warnings_of(theme),
              (std::vector<std::string>{
                  "t.json:3:66: magnitude 1.5 clamped to 1, as feedbackd clamps it",
                  "t.json:3:71: magnitude -0.5 clamped to 0, as feedbackd clamps it",
                  "t.json:5:1: the VibraPattern for \"uneven\" has 2 magnitudes but 1 durations: "
                  "feedbackd plays nothing",
                  "t.json:6:1: the VibraPattern for \"half\" lacks \"magnitudes\" or "
                  "\"durations\": feedbackd plays nothing",
                  "t.json:8:14: a VibraPattern lasts as long as its durations together: "
                  "\"duration\" ignored"}));
}

TEST(FeedbackdTheme, ReadsARumblesMagnitudeAndKeepsTheDefaultForOneOutOfRange) {
    const auto theme = theme_from(feedbackd_theme(
        R"({"event-name": "a", "type": "VibraRumble", "duration": 100, "magnitude": 0.8},
{"event-name": "b", "type": "VibraRumble", "duration": 100},
{"event-name": "c", "type": "VibraRumble", "duration": 100, "magnitude": 1},
{"event-name": "d", "type": "VibraRumble", "duration": 100, "magnitude": 2})"));
    EXPECT_EQ(vibra(theme, "a"), rumble_feedback(100, 1, 0, 0.8));
    EXPECT_EQ(vibra(theme, "b").magnitude, 0.5);  // feedbackd 0.8's default
    EXPECT_EQ(vibra(theme, "c").magnitude, 1.0);
    EXPECT_EQ(vibra(theme, "d").magnitude, 0.5);
    EXPECT_EQ(warnings_of(theme),
              std::vector<std::string>{
                  "t.json:6:74: magnitude 2 is outside 0 to 1: feedbackd keeps its default, 0.5"});
}

TEST(FeedbackdTheme, TellsOldPeriodicMagnitudesFromNewOnesAsFeedbackd08Does) {
    // Up to 1 is feedbackd 0.8's scale, whole or not; above it, 0.0.3's 0..32767.
    const auto theme = theme_from(feedbackd_theme(
        R"({"event-name": "float", "type": "VibraPeriodic", "magnitude": 0.25},
{"event-name": "one", "type": "VibraPeriodic", "magnitude": 1},
{"event-name": "two", "type": "VibraPeriodic", "magnitude": 2},
{"event-name": "full", "type": "VibraPeriodic", "magnitude": 32767, "fade-in-level": 16384},
{"event-name": "over", "type": "VibraPeriodic", "magnitude": 32768},
{"event-name": "negative", "type": "VibraPeriodic", "magnitude": -0.1, "fade-in-time": 0})"));
    EXPECT_EQ(vibra(theme, "float"), periodic_feedback(1000, 0.25, 0.0, 500));
    EXPECT_EQ(vibra(theme, "one").magnitude, 1.0);
    EXPECT_EQ(vibra(theme, "two").magnitude, 2.0 / 32767.0);
    EXPECT_EQ(vibra(theme, "full").magnitude, 1.0);
    EXPECT_EQ(vibra(theme, "full").fade_in_level, 16384.0 / 32767.0);
    EXPECT_EQ(vibra(theme, "over").magnitude, 1.0);
    EXPECT_EQ(vibra(theme, "negative"), periodic_feedback(1000, 0.5, 0.0, 0));
    const auto warnings = warnings_of(theme);
    ASSERT_EQ(warnings.size(), 5u);
    EXPECT_EQ(warnings[0],
              "t.json:5:61: magnitude 2 is of feedbackd 0.0.3's scale (0 to 32767): read as "
              "6.103701895199438e-05 of full (feedbackd 0.8 divides by 65535); please update the "
              "theme");
    EXPECT_EQ(warnings[1].substr(0, 30), "t.json:6:62: magnitude 32767 i");
    EXPECT_EQ(warnings[2].substr(0, 30), "t.json:6:86: fade-in-level 163");
    EXPECT_EQ(warnings[4],
              "t.json:8:66: magnitude -0.1 is outside 0 to 1: feedbackd keeps its default, 0.5");
}

TEST(FeedbackdTheme, SkipsAnUnknownFeedbackTypeWithAWarningAsFeedbackdDoes) {
    // feedbackd makes a Dummy of it, so it replaces an earlier feedback of its event and
    // profile; the first letter may be lower case, as feedbackd capitalizes it.
    const auto theme = theme_from(feedbackd_theme(
        R"({"event-name": "e", "type": "VibraRumble", "duration": 100},
{"event-name": "e", "type": "VibraWobble"},
{"event-name": "f", "type": "vibraRumble", "duration": 30},
{"event-name": "g"})"));
    EXPECT_EQ(theme.lookup("e", Profile::quiet), nullptr);
    EXPECT_EQ(vibra(theme, "f"), rumble_feedback(30, 1, 0));
    EXPECT_EQ(theme.lookup("g", Profile::quiet), nullptr);
    EXPECT_EQ(
        warnings_of(theme),
        (std::vector<std::string>{
            "t.json:4:1: a second feedback for \"e\" in profile \"quiet\": feedbackd keeps one "
            "per event and profile, the last",
            "t.json:4:29: unknown feedback type \"VibraWobble\" skipped (feedbackd 0.8.2 knows "
            "Sound, Led, Dummy, VibraRumble, VibraPeriodic and VibraPattern)",
            "t.json:6:1: the feedback for \"g\" has no \"type\": no vibration"}));
}

TEST(FeedbackdTheme, ReadsPastUnknownMembersAndProfilesWithAWarning) {
    const auto theme = theme_from(
        R"({"name": "t", "version": 2, "profiles": [
  {"name": "loud", "feedbacks": [{"event-name": "e", "type": "VibraRumble"}]},
  {"name": "quiet", "colour": "red", "feedbacks": [
    {"event-name": "e", "type": "VibraRumble", "duration": 10, "sharpness": 0.5}]}]})");
    EXPECT_EQ(vibra(theme, "e"), rumble_feedback(10, 1, 0));
    EXPECT_EQ(warnings_of(theme),
              (std::vector<std::string>{
                  "t.json:1:15: unknown member \"version\" ignored",
                  "t.json:2:12: unknown profile \"loud\" (feedbackd plays full, quiet or silent): "
                  "its feedbacks are never played",
                  "t.json:3:21: unknown member \"colour\" of profile \"quiet\" ignored",
                  "t.json:4:64: unknown member \"sharpness\" of a VibraRumble feedback ignored"}));
}

TEST(FeedbackdTheme, KeepsTheLastFeedbackOfAnEventAndProfileAndALaterProfileReplacesAnEarlier) {
    // A Sound after a vibra replaces it (feedbackd keeps one feedback per event and profile);
    // in another profile the vibra still plays.
    const auto theme = theme_from(
        R"({"name": "t", "profiles": [
  {"name": "quiet", "feedbacks": [{"event-name": "e", "type": "VibraRumble", "duration": 10},
                                  {"event-name": "e", "type": "Sound", "effect": "bell"}]},
  {"name": "silent", "feedbacks": [{"event-name": "e", "type": "VibraRumble", "duration": 20}]},
  {"name": "silent", "feedbacks": [{"event-name": "f", "type": "VibraRumble", "duration": 30}]}
]})");
    EXPECT_EQ(theme.lookup("e", Profile::quiet), nullptr);
    EXPECT_EQ(theme.lookup("e", Profile::silent), nullptr);
    EXPECT_EQ(vibra(theme, "f", Profile::silent), rumble_feedback(30, 1, 0));
    EXPECT_EQ(vibra(theme, "f", Profile::full), rumble_feedback(30, 1, 0));
    EXPECT_EQ(theme.warnings.size(), 2u);
}

TEST(FeedbackdTheme, AcceptsEachLimitAtItsEdgeAndRefusesOneMore) {
    const auto at_edge = theme_from(feedbackd_theme(
        R"({"event-name": "long", "type": "VibraRumble", "duration": 3600000, "count": 1},
{"event-name": "pattern", "type": "VibraPattern", "magnitudes": [1, 1],
 "durations": [3599999, 1]},
{"event-name": "zero", "type": "VibraPeriodic", "duration": 0, "fade-in-time": 0})"));
    EXPECT_EQ(vibra(at_edge, "long").duration_ms, 3'600'000u);
    EXPECT_EQ(vibra(at_edge, "pattern").duration_ms, 3'600'000u);
    EXPECT_TRUE(vibra_pattern(vibra(at_edge, "zero")).empty());
    EXPECT_EQ(error_of(feedbackd_theme(
                  R"({"event-name": "e", "type": "VibraRumble", "duration": 3600001})")),
              "t.json:3:56: expected a whole number from 0 to 3600000, found 3600001");
    EXPECT_EQ(error_of(feedbackd_theme(
                  R"({"event-name": "e", "type": "VibraRumble", "duration": 100, "count": 0})")),
              "t.json:3:70: expected a whole number from 1 to 2147483647, found 0");
    EXPECT_EQ(error_of(feedbackd_theme(R"({"event-name": "e", "type": "VibraPattern",
  "magnitudes": [1, 1], "durations": [3600000, 1]})")),
              "t.json:4:48: the pattern lasts longer than an hour (3600000 ms)");
}

TEST(FeedbackdTheme, RefusesAShapeFeedbackdCannotUseWhereItStands) {
    EXPECT_EQ(error_of(feedbackd_theme(R"({"type": "VibraRumble"})")),
              "t.json:3:1: missing \"event-name\"");
    EXPECT_EQ(error_of(feedbackd_theme(R"({"event-name": "e", "type": 7})")),
              "t.json:3:29: expected a string, found 7");
    EXPECT_EQ(error_of(feedbackd_theme(
                  R"({"event-name": "e", "type": "VibraRumble", "magnitude": "high"})")),
              "t.json:3:57: expected a number, found \"high\"");
    EXPECT_EQ(error_of(feedbackd_theme(
                  R"({"event-name": "e", "type": "VibraRumble", "duration": 10.5})")),
              "t.json:3:56: expected a whole number from 0 to 3600000, found 10.5");
    EXPECT_EQ(error_of(R"({"name": "t", "profiles": {"quiet": []}})"),
              "t.json:1:27: expected an array ([...]), found an object");
    EXPECT_EQ(error_of("[]"), "t.json:1:1: a theme is a JSON object");
}

// -- Parent themes -------------------------------------------------------------------------

// A user's config directory, the system's data directory and a builtin directory, as feedbackd
// has them, with theme files the test writes.
class ParentThemes : public ::testing::Test {
  protected:
    ParentThemes() {
        search.config_home = dir.path() / "config";
        search.data_dirs = {dir.path() / "data"};
        search.builtin_dir = dir.path() / "builtin";
    }
    std::string user_theme(const std::string& name, const std::string& text) {
        return dir.write("config/feedbackd/themes/" + name + ".json", text).string();
    }
    std::string system_theme(const std::string& name, const std::string& text) {
        return dir.write("data/feedbackd/themes/" + name + ".json", text).string();
    }
    // A theme giving each event a rumble of that duration in profile `profile`.
    static std::string rumbles(const std::string& name, const std::string& parent,
                               const std::vector<std::pair<std::string, int>>& events,
                               const std::string& profile = "quiet") {
        std::string feedbacks;
        for (const auto& [event, ms] : events) {
            feedbacks += std::string(feedbacks.empty() ? "" : ",\n") + "{\"event-name\": \"" +
                         event + "\", \"type\": \"" + (ms < 0 ? "Sound" : "VibraRumble") +
                         "\", \"duration\": " + std::to_string(ms < 0 ? 0 : ms) + "}";
        }
        return "{\"name\": \"" + name + "\"" +
               (parent.empty() ? "" : ", \"parent-name\": \"" + parent + "\"") +
               ",\n \"profiles\": [{\"name\": \"" + profile + "\", \"feedbacks\": [\n" + feedbacks +
               "]}]}";
    }

    testing::TempDir dir;
    ThemeSearch search;
};

TEST_F(ParentThemes, AreMergedUnderTheThemeAsFeedbackdMergesThem) {
    system_theme("default", rumbles("default", "", {{"a", 100}, {"b", 200}, {"c", 300}}));
    // The child replaces a, hides b behind a Sound, adds d; c stays the parent's.
    const auto path =
        user_theme("custom", rumbles("custom", "default", {{"a", 10}, {"b", -1}, {"d", 40}}));
    const Theme theme = load_theme(path, search);
    EXPECT_EQ(theme.name, "custom");
    EXPECT_EQ(vibra(theme, "a"), rumble_feedback(10, 1, 0));
    EXPECT_EQ(theme.lookup("b", Profile::quiet), nullptr);
    EXPECT_EQ(vibra(theme, "c"), rumble_feedback(300, 1, 0));
    EXPECT_EQ(vibra(theme, "d"), rumble_feedback(40, 1, 0));
    EXPECT_TRUE(theme.warnings.empty());
}

TEST_F(ParentThemes, FindTheUsersThemeFirstAndTheDevicesThemeOnceForDefault) {
    // feedbackd's own test: custom (the user's) over the device theme "replace" over default.
    search.compatibles = {"doesnotexist", "replace"};
    system_theme("default", rumbles("default", "", {{"a", 100}, {"b", 200}, {"c", 300}}));
    system_theme("replace", rumbles("$device", "default", {{"a", 16}, {"b", 32}}));
    const auto path = user_theme("custom", rumbles("custom", "default", {{"b", 48}}));
    const Theme theme = load_theme(path, search);
    EXPECT_EQ(vibra(theme, "a"), rumble_feedback(16, 1, 0));
    EXPECT_EQ(vibra(theme, "b"), rumble_feedback(48, 1, 0));
    EXPECT_EQ(vibra(theme, "c"), rumble_feedback(300, 1, 0));
    // A user's own "default" comes before the system's.
    user_theme("default", rumbles("default", "", {{"c", 5}}));
    search.compatibles.clear();
    EXPECT_EQ(vibra(load_theme(path, search), "c"), rumble_feedback(5, 1, 0));
}

TEST_F(ParentThemes, FallBackToTheDefaultThemeForAParentNotFoundWithAWarning) {
    system_theme("default", rumbles("default", "", {{"a", 100}}));
    const auto path = user_theme("custom", rumbles("custom", "nowhere", {}));
    const Theme theme = load_theme(path, search);
    EXPECT_EQ(vibra(theme, "a"), rumble_feedback(100, 1, 0));
    EXPECT_EQ(
        warnings_of(theme),
        std::vector<std::string>{path + ":1:35: theme \"nowhere\" not found, falling back to the "
                                        "default theme"});
}

TEST_F(ParentThemes, MayBeTenDeepAndNotEleven) {
    for (int i = 1; i <= 10; ++i) {
        user_theme("t" + std::to_string(i),
                   rumbles("t" + std::to_string(i), i < 10 ? "t" + std::to_string(i + 1) : "",
                           {{"e" + std::to_string(i), i}}));
    }
    const auto path = dir.write("t0.json", rumbles("t0", "t1", {{"e0", 1000}})).string();
    const Theme ten = load_theme(path, search);
    EXPECT_EQ(vibra(ten, "e10"), rumble_feedback(10, 1, 0));
    EXPECT_EQ(vibra(ten, "e0"), rumble_feedback(1000, 1, 0));
    user_theme("t10", rumbles("t10", "t11", {}));
    user_theme("t11", rumbles("t11", "", {}));
    EXPECT_EQ(testing::first_diagnostic([&] { load_theme(path, search); }).message,
              "more than 10 parent themes (feedbackd's limit): " + path + " and then " +
                  (dir.path() / "config/feedbackd/themes/t1.json").string() + " ... " +
                  (dir.path() / "config/feedbackd/themes/t11.json").string());
    // A theme naming itself is such a chain.
    const auto loop = user_theme("loop", rumbles("loop", "loop", {}));
    EXPECT_THROW(load_theme(loop, search), DocumentError);
}

TEST_F(ParentThemes, RefuseWhatFeedbackdRefusesAndNameTheFile) {
    system_theme("default", rumbles("default", "", {}));
    EXPECT_EQ(error_of(rumbles("default", "other", {})),
              "t.json:1:36: the default theme cannot name a parent");
    EXPECT_EQ(error_of(rumbles("", "", {})),
              "t.json:1:10: a feedbackd theme needs a \"name\" that is not empty");
    EXPECT_EQ(error_of("{\"profiles\": []}"),
              "t.json: a feedbackd theme needs a \"name\" that is not empty");
    // The default theme nowhere: feedbackd's last resort, its builtin directory, has none.
    EXPECT_EQ(error_of(rumbles("custom", "default", {})),
              "/nonexistent/feedbackd/themes/default.json: cannot open: No such file or "
              "directory");
    const auto parent = system_theme("default", vibscore_theme(""));
    EXPECT_EQ(error_of(rumbles("custom", "default", {}), search),
              parent + ": a parent theme must be a feedbackd theme, not vibscore's");
    system_theme("default", "{\"name\": \"default\", \"profiles\": 3}");
    EXPECT_EQ(error_of(rumbles("custom", "default", {}), search),
              parent + ":1:33: expected an array ([...]), found 3");
}

// -- vibscore's own theme ------------------------------------------------------------------

TEST(VibscoreTheme, TheShippedThemeNamesShippedScoresForEveryEventFeedbackdVibratesFor) {
    const Theme shipped =
        load_theme(testing::required_env("VIBSCORE_FEEDBACK_THEME"), no_parents());
    const auto clefs = std::filesystem::path(testing::required_env("VIBSCORE_CLEFS"));
    for (const auto& [event, levels] : shipped.events()) {
        for (const auto& [profile, entry] : levels) {
            EXPECT_TRUE(std::filesystem::exists(clefs / (entry.score + ".score.xml")))
                << event << ": " << entry.score;
            EXPECT_NO_THROW(load_score_file(clefs / (entry.score + ".score.xml"))) << event;
            EXPECT_TRUE(daemon::parse_usage(entry.usage)) << event;
        }
    }
    // feedbackd 0.8's new events, whatever release this runs on.
    EXPECT_EQ(shipped.lookup("notification-new-generic", Profile::quiet)->score,
              "notification-new-generic");
    EXPECT_EQ(shipped.lookup("message-new-cellbroadcast", Profile::quiet)->score,
              "message-new-cellbroadcast");
    EXPECT_EQ(shipped.lookup("message-new-cellbroadcast", Profile::quiet)->usage, "alarm");
    for (const auto& path : shipped_feedbackd_themes()) {
        const Theme feedbackd = load_theme(path, no_parents());
        for (const auto& [event, levels] : feedbackd.events()) {
            for (const auto profile : {Profile::quiet, Profile::full}) {
                if (feedbackd.lookup(event, profile) != nullptr) {
                    EXPECT_NE(shipped.lookup(event, profile), nullptr) << path << ": " << event;
                }
            }
        }
    }
    EXPECT_EQ(shipped.lookup("button-pressed", Profile::silent), nullptr);
}

TEST(VibscoreTheme, AnEntryOfALowerProfilePlaysInTheHigherOnesUnlessTheyHaveTheirOwn) {
    const auto theme = theme_from(
        R"({"vibscore-theme": 1, "name": "t", "profiles": {
             "quiet": {"a": {"score": "alarm", "usage": "alarm"}, "b": {"score": "touch-tick"}},
             "full": {"a": {"score": "ringtone", "usage": "alarm", "intensity": 0.5,
                            "clef": "erm-phone"}}}})");
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
    EXPECT_EQ(error_of("{\"name\": \"x\",\n \"profiles\": [1e999]}"),
              "t.json:2:15: number 1e999 is too large");
}

TEST(ThemeErrors, AWrongValueIsNamedWhereItStands) {
    EXPECT_EQ(error_of(vibscore_theme("  \"e\": {\"score\": \"x\", \"usage\": \"loud\"}")),
              "t.json:3:32: unknown usage \"loud\" (expected ringtone, alarm, notification, "
              "communication, accessibility, hardware-feedback, touch, media)");
    EXPECT_EQ(error_of(vibscore_theme("  \"e\": {\"score\": 7}")),
              "t.json:3:18: expected a string, found 7");
    EXPECT_EQ(error_of(vibscore_theme("  \"e\": {\"score\": \"x\", \"volume\": 1}")),
              "t.json:3:23: unknown member \"volume\" (expected score, usage, intensity or clef)");
    EXPECT_EQ(error_of(vibscore_theme("  \"e\": {\"usage\": \"touch\"}")),
              "t.json:3:8: missing \"score\"");
    EXPECT_EQ(error_of(vibscore_theme("  \"e\": {\"score\": \"x\", \"intensity\": 1.5}")),
              "t.json:3:36: expected a number from 0 to 1, found 1.5");
    EXPECT_EQ(error_of(R"({"vibscore-theme": 1, "name": "t", "profiles": {"loud": {}}})"),
              "t.json:1:49: unknown profile \"loud\" (expected full, quiet or silent)");
    EXPECT_EQ(error_of(R"({"vibscore-theme": 2, "name": "t", "profiles": {}})"),
              "t.json:1:20: expected a whole number from 1 to 1, found 2");
}

TEST(ThemeErrors, AFileThatCannotBeReadSaysSo) {
    EXPECT_EQ(testing::first_diagnostic([] {
                  load_theme("/nonexistent/theme.json", no_parents());
              }).message,
              "cannot open: No such file or directory");
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
