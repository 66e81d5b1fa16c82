// The user's own score per event: its file (read, stored, kept when it does not read, its
// names at their limits) and how the event table plays it.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <thread>

#include "feedback/event_table.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/user_scores.hpp"
#include "feedback/user_scores_writer.hpp"
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
    // Larger than the reader's limit: refused as a whole, by name, and never written over.
    const auto large = dir.write("large.json", std::string(max_json_file_bytes + 1, ' '));
    EXPECT_EQ(format(testing::first_diagnostic([&] { read(large); })),
              large.string() + ": larger than 1048576 bytes, the limit for a JSON file");
    EXPECT_THROW(store_user_score(large, "c", "d"), DocumentError);
    EXPECT_EQ(std::filesystem::file_size(large), max_json_file_bytes + 1);
}

// One entry the user mistyped does not cost the others: each is read past with a warning at
// its place.
TEST(UserScoresFile, KeepsEveryEntryThatReadsAndWarnsOfEachThatDoesNot) {
    testing::TempDir dir;
    const auto file =
        dir.write("feedback.json",
                  R"({"events": {"a": 3, "B": "c", "d": "E", "phone-incoming-call": "ring"}})");
    std::vector<Diagnostic> warnings;
    EXPECT_EQ(read_user_scores(file, warnings), (UserScores{{"phone-incoming-call", "ring"}}));
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(format(warnings[0]),
              file.string() + ":1:18: expected a string, found 3: the entry is ignored");
    EXPECT_EQ(format(warnings[1]),
              file.string() +
                  ":1:21: event \"B\" is not an event name (a name is 1 to 64 of a-z 0-9 . _ -, "
                  "starting with a letter or a digit): the entry is ignored");
    EXPECT_EQ(format(warnings[2]),
              file.string() +
                  ":1:36: score \"E\" is not a score name (a name is 1 to 64 of a-z 0-9 . _ -, "
                  "starting with a letter or a digit): the entry is ignored");
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

TEST(EventNames, AreLowerCaseWordsAndHyphensOfAtMostSixtyFourCharacters) {
    EXPECT_TRUE(is_event_name("phone-incoming-call"));
    EXPECT_TRUE(is_event_name("a"));
    EXPECT_TRUE(is_event_name("button-2-pressed"));
    const std::string longest = std::string(31, 'e') + "-" + std::string(32, 'e');
    ASSERT_EQ(longest.size(), 64u);
    EXPECT_TRUE(is_event_name(longest));
    EXPECT_FALSE(is_event_name(longest + "e"));
    EXPECT_FALSE(is_event_name(""));
    EXPECT_FALSE(is_event_name("Phone-incoming-call"));
    EXPECT_FALSE(is_event_name("phone-incoming-cAll"));
    EXPECT_FALSE(is_event_name("phone_incoming"));
    EXPECT_FALSE(is_event_name("phone.incoming"));
    EXPECT_FALSE(is_event_name("-phone"));
    EXPECT_FALSE(is_event_name("phone-"));
    EXPECT_FALSE(is_event_name("phone--call"));
}

std::string event_number(std::size_t n) {
    return "event-" + std::to_string(n);
}

TEST(UserScoresFile, TakesTheTwoHundredFiftySixthEventAndRefusesTheTwoHundredFiftySeventh) {
    testing::TempDir dir;
    const auto file = dir.path() / "feedback.json";
    for (std::size_t n = 1; n <= kMaxAssignments; ++n) {
        store_user_score(file, event_number(n), "s");
    }
    EXPECT_EQ(read(file).size(), 256u);
    const auto before = testing::read_file(file);
    try {
        store_user_score(file, event_number(257), "s");
        ADD_FAILURE() << "the 257th event was stored";
    } catch (const AssignmentLimit& error) {
        EXPECT_EQ(std::string(error.what()),
                  "256 events already have a score of your own in " + file.string() +
                      ", the limit is 256: give one back to the theme first (vibscore assign "
                      "EVENT --default)");
    }
    EXPECT_EQ(testing::read_file(file), before);
    // At the limit an event already chosen takes another score, and one given back makes room.
    store_user_score(file, event_number(1), "t");
    EXPECT_EQ(read(file).at(event_number(1)), "t");
    store_user_score(file, event_number(2), "");
    store_user_score(file, event_number(257), "s");
    EXPECT_EQ(read(file).size(), 256u);
}

// A file of 256 entries with the longest names this code writes is a fraction of the reader's
// limit; one padded by hand to exactly the limit reads back whole, and a byte more is refused.
TEST(UserScoresFile, AtTheReadersLimitReadsBackWholeAndIsNeverWrittenPastIt) {
    testing::TempDir dir;
    const auto file = dir.path() / "feedback.json";
    for (std::size_t n = 1; n <= kMaxAssignments; ++n) {
        const auto event = event_number(n);
        store_user_score(file, event + "-" + std::string(63 - event.size(), 'x'),
                         std::string(64, 's'));
    }
    const auto written = testing::read_file(file);
    EXPECT_LT(written.size(), 40'000u);
    auto padded = written;
    padded.insert(padded.size() - 2, max_json_file_bytes - written.size(), ' ');
    ASSERT_EQ(padded.size(), max_json_file_bytes);
    const auto at_limit = dir.write("at-limit.json", padded);
    const auto scores = read(at_limit);
    EXPECT_EQ(scores.size(), 256u);
    EXPECT_EQ(scores.at("event-256-" + std::string(54, 'x')), std::string(64, 's'));

    // Room taken by a member written by hand: a store that would pass the limit is refused
    // and the file stays as it was, readable.
    const std::string head = "{\"note\": \"";
    const std::string tail = "\", \"events\": {\"a\": \"b\"}}";
    const auto crowded = dir.write(
        "crowded.json",
        head + std::string(max_json_file_bytes - 100 - head.size() - tail.size(), 'n') + tail);
    EXPECT_THROW(store_user_score(crowded, "phone-incoming-call", std::string(64, 's')),
                 AssignmentLimit);
    EXPECT_EQ(std::filesystem::file_size(crowded), max_json_file_bytes - 100);
    EXPECT_EQ(read(crowded), (UserScores{{"a", "b"}}));
}

TEST(UserScoresFile, ReadsTheFirstTwoHundredFiftySixEntriesOfALongerFileAndWarns) {
    testing::TempDir dir;
    std::string text = "{\"events\": {";
    for (std::size_t n = 1; n <= kMaxAssignments + 2; ++n) {
        text += (n > 1 ? ", \"" : "\"") + event_number(n) + "\": \"s\"";
    }
    const auto file = dir.write("feedback.json", text + "}}");
    std::vector<Diagnostic> warnings;
    const auto scores = read_user_scores(file, warnings);
    EXPECT_EQ(scores.size(), 256u);
    EXPECT_TRUE(scores.contains(event_number(256)));
    EXPECT_FALSE(scores.contains(event_number(257)));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].message.find("more than 256 events have a score of your own: this one "
                                       "and those after it are ignored"),
              std::string::npos);
}

TEST(UserScoresFile, StaleTemporariesOfItAreRemovedAndNothingElse) {
    testing::TempDir dir;
    const auto file = dir.write("feedback.json", "{}");
    dir.write(".feedback.json.tmp-Ab3dE9", "{\"events\": {");
    dir.write(".feedback.json.tmp-zzzzzz", "");
    dir.write(".other.json.tmp-Ab3dE9", "");
    dir.write("feedback.json.tmp-notmine", "");
    const auto removed = remove_stale_temporaries_of(file);
    EXPECT_EQ(removed.size(), 2u);
    EXPECT_EQ(testing::file_names(dir.path()),
              (std::vector<std::string>{".other.json.tmp-Ab3dE9", "feedback.json",
                                        "feedback.json.tmp-notmine"}));
    // No directory yet: nothing to remove.
    EXPECT_TRUE(remove_stale_temporaries_of(dir.path() / "none/feedback.json").empty());
}

// -- Stored off the bus thread ----------------------------------------------------------------

TEST(UserScoresWriter, StoresInOrderOffTheLoopsThreadAndRefusesTheThirtyThirdWaitingStore) {
    testing::TempDir dir;
    const auto file = dir.path() / "feedback.json";
    // A FIFO holds the first store where a slow disk would, for as long as the test wants.
    ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
    daemon::EventLoop loop;
    std::vector<std::string> outcomes;
    bool on_loop_thread = true;
    const auto loop_thread = std::this_thread::get_id();
    UserScoresWriter writer(loop, file);
    const auto done = [&](const std::string& what) {
        return [&, what](std::exception_ptr error) {
            on_loop_thread = on_loop_thread && std::this_thread::get_id() == loop_thread;
            try {
                if (error) {
                    std::rethrow_exception(error);
                }
                outcomes.push_back(what + " stored");
            } catch (const AssignmentLimit&) {
                outcomes.push_back(what + " over the limit");
            } catch (const std::exception& other) {
                outcomes.push_back(what + ": " + other.what());  // seen in the failure
            }
            if (outcomes.size() == 1 + UserScoresWriter::kMaxWaiting) {
                loop.exit(0);
            }
        };
    };
    ASSERT_TRUE(writer.submit("event-0", "s", done("event-0")));
    // The thread took the first store and waits in the file's open: the queue is empty.
    const int held = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
    ASSERT_GE(held, 0);
    for (std::size_t n = 1; n <= UserScoresWriter::kMaxWaiting; ++n) {
        EXPECT_TRUE(writer.submit(event_number(n), "s", done(event_number(n)))) << n;
    }
    EXPECT_FALSE(writer.submit("event-33", "s", done("event-33")));
    // The first store reads the FIFO, then writes a file over it.
    const std::string full = [] {
        std::string text = "{\"events\": {";
        for (std::size_t n = 1; n <= kMaxAssignments - 2; ++n) {
            text += "\"other-" + std::to_string(n) + "\": \"s\", ";
        }
        return text + "\"event-0\": \"s\", \"event-5\": \"s\"}}";
    }();
    EXPECT_EQ(::write(held, full.data(), full.size()), static_cast<ssize_t>(full.size()));
    ::close(held);
    EXPECT_EQ(loop.run(), 0);
    EXPECT_TRUE(on_loop_thread);
    // In the order asked: the file held 256 events, so only those already in it take a score.
    ASSERT_EQ(outcomes.size(), 33u);
    EXPECT_EQ(outcomes[0], "event-0 stored");
    EXPECT_EQ(outcomes[1], "event-1 over the limit");
    EXPECT_EQ(outcomes[5], "event-5 stored");
    EXPECT_EQ(outcomes[32], "event-32 over the limit");
    EXPECT_EQ(read(file).size(), 256u);
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
