// The bash completion installed for vibscore, run in a real bash against a real daemon.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include "tests/support/daemon_fixture.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using ::testing::Not;

class Completion : public ::testing::Test {
  protected:
    DaemonFixture daemon{"drivers-dir = " + testing::required_env("VIBSCORE_EXAMPLE_DRIVERS")};

    const std::filesystem::path client = testing::required_env("VIBSCORE");

    // What bash offers after `line` (the last word is the one being completed). The client's
    // folder is on PATH unless the line names the client by its path.
    std::string complete(const std::string& line, bool client_on_path = true) const {
        const std::string path =
            client_on_path ? client.parent_path().string() + ":$PATH" : "/usr/bin:/bin";
        const std::string script =
            "PATH=" + path + "; source " + testing::required_env("VIBSCORE_COMPLETION") +
            "; COMP_LINE='" + line +
            "'; read -ra COMP_WORDS <<< \"$COMP_LINE\"; [[ $COMP_LINE == *' ' ]] && "
            "COMP_WORDS+=(''); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _vibscore; "
            "printf '%s\\n' \"${COMPREPLY[@]}\" | sort";
        const auto result = testing::run_command({"/bin/bash", "-c", script});
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return result.out;
    }
};

TEST_F(Completion, OffersVerbsOptionsAndTheDaemonsNames) {
    EXPECT_EQ(complete("vibscore dr"), "driver\ndrivers\n");
    EXPECT_EQ(complete("vibscore play --usage al"), "alarm\n");
    EXPECT_EQ(complete("vibscore play --w"), "--wait\n");
    EXPECT_THAT(complete("vibscore play notification-"), HasSubstr("notification-message\n"));
    EXPECT_THAT(complete("vibscore get clef lra-"), HasSubstr("lra-phone\n"));
    EXPECT_EQ(complete("vibscore get "), "clef\nscore\n");
    EXPECT_EQ(complete("vibscore driver tr"), "trace\n");
    EXPECT_THAT(complete("vibscore list "), Not(HasSubstr("ringtone")));
}

// The verbs, each verb's options and which options take a value come from the client's verb table
// (vibscore --completion-words), not from a list in the script.
TEST_F(Completion, OffersTheVerbTablesVerbsAndEachVerbsOwnOptions) {
    const auto words = "\n" + complete("vibscore ");
    for (const char* verb : {"check", "render", "convert", "clef", "info", "play", "stop", "list",
                             "get", "compose", "delete", "drivers", "driver", "show", "assign",
                             "calibrate", "edit", "--help", "--version"}) {
        EXPECT_THAT(words, HasSubstr(std::string("\n") + verb + "\n")) << verb;
    }
    EXPECT_EQ(std::count(words.begin(), words.end(), '\n'), 20) << words;
    EXPECT_EQ(complete("vibscore drivers --"), "--help\n");
    EXPECT_EQ(complete("vibscore calibrate --e"), "--estimate\n");
    EXPECT_EQ(complete("vibscore stop --"), "--all\n--help\n");
    // A valued option's value is not the score: the score is still the first word.
    EXPECT_THAT(complete("vibscore play --repeat 2 notification-"),
                HasSubstr("notification-message\n"));
    // A flag takes none: the kind is the first word, the name the second.
    EXPECT_THAT(complete("vibscore get --device clef lra-"), HasSubstr("lra-phone\n"));
}

TEST_F(Completion, OffersAssignItsOptionsTheUsersEventsAndTheRegistrysScores) {
    // Without vibscore-feedback, the events are those of the user's own file.
    const testing::TempDir config;
    config.write("vibscore/feedback.json", R"({"events": {"phone-incoming-call": "alarm"}})");
    const auto saved = [](const char* name) {
        const char* value = std::getenv(name);
        return value != nullptr ? std::optional<std::string>(value) : std::nullopt;
    };
    const auto config_home = saved("XDG_CONFIG_HOME");
    const auto session_bus = saved("DBUS_SESSION_BUS_ADDRESS");
    ::setenv("XDG_CONFIG_HOME", config.path().c_str(), 1);
    ::setenv("DBUS_SESSION_BUS_ADDRESS", "unix:path=/nonexistent", 1);
    EXPECT_EQ(complete("vibscore ass"), "assign\n");
    EXPECT_EQ(complete("vibscore assign --d"), "--default\n");
    EXPECT_EQ(complete("vibscore assign --f"), "--force\n");
    EXPECT_EQ(complete("vibscore assign phone-"), "phone-incoming-call\n");
    EXPECT_THAT(complete("vibscore assign phone-incoming-call ring"), HasSubstr("ringtone\n"));
    for (const auto& [name, value] : {std::pair{"XDG_CONFIG_HOME", config_home},
                                      std::pair{"DBUS_SESSION_BUS_ADDRESS", session_bus}}) {
        if (value) {
            ::setenv(name, value->c_str(), 1);
        } else {
            ::unsetenv(name);
        }
    }
}

TEST_F(Completion, FoldersEndInASlashAndFilesFollowTheVerbsPattern) {
    const testing::TempDir dir;
    std::filesystem::create_directory(dir.path() / "scores");
    for (const char* name : {"a.score.xml", "take.csv", "take.wav", "notes.txt"}) {
        dir.write(name, "x");
    }
    const std::string root = dir.path().string() + "/";
    EXPECT_EQ(complete("vibscore check " + root), root + "a.score.xml\n" + root + "scores/\n");
    EXPECT_EQ(complete("vibscore render a.score.xml --out " + root),
              root + "scores/\n" + root + "take.csv\n" + root + "take.wav\n");
    EXPECT_EQ(complete("vibscore play --clefs " + root), root + "scores/\n");
}

TEST_F(Completion, OffersEveryAliasAndTheClefsFolderOption) {
    EXPECT_EQ(complete("vibscore edit --b"), "--button-map\n--buttons\n");
    EXPECT_EQ(complete("vibscore show --col"), "--color\n--colour\n");
    EXPECT_EQ(complete("vibscore check --c"), "--clefs\n");
}

TEST_F(Completion, OffersClefFitItsOptionsAndTheDaemonsClefs) {
    EXPECT_EQ(complete("vibscore cle"), "clef\n");
    EXPECT_EQ(complete("vibscore clef "), "fit\n");
    EXPECT_THAT(complete("vibscore clef fit lra-"), HasSubstr("lra-phone\n"));
    EXPECT_EQ(complete("vibscore clef fit lra-phone --o"), "--output\n");
    EXPECT_THAT(complete("vibscore clef fit lra-phone --actuator dae"), HasSubstr("daemon\n"));
}

TEST_F(Completion, WorksForTheClientInTheBuildTreeNotOnPath) {
    const std::string built = client.string();
    EXPECT_EQ(complete(built + " driver tr", false), "trace\n");
    EXPECT_THAT(complete(built + " get clef lra-", false), HasSubstr("lra-phone\n"));
    const auto registered =
        testing::run_command({"/bin/bash", "-c",
                              "source " + testing::required_env("VIBSCORE_COMPLETION") +
                                  " && complete -p build/client/vibscore"});
    EXPECT_EQ(registered.exit_code, 0) << registered.err;
}

TEST_F(Completion, OffersConvertItsOptionsFormatsAndPictureFiles) {
    EXPECT_EQ(complete("vibscore conv"), "convert\n");
    EXPECT_EQ(complete("vibscore convert --t"), "--to\n--track\n");
    // Only what convert reads after --from, only what it writes after --to.
    EXPECT_EQ(complete("vibscore convert a.mid b.score.xml --from "),
              "ahap\nandroid-json\nandroid-xml\nmidi\nrtttl\nscore\n");
    EXPECT_EQ(complete("vibscore convert a.mid b.score.xml --to "),
              "ahap\nandroid-envelope\nandroid-json\nandroid-xml\nmidi\nscore\n");
    EXPECT_EQ(complete("vibscore convert a.rtttl b.score.xml --clefs"), "--clefs\n");
    EXPECT_EQ(complete("vibscore convert x.ahap --to android-"),
              "android-envelope\nandroid-json\nandroid-xml\n");
    EXPECT_EQ(complete("vibscore show ringtone --s"), "--svg\n");
    EXPECT_EQ(complete("vibscore show lra-phone --png x.png --ac"), "--actuator\n");
    EXPECT_EQ(complete("vibscore render x.xml --p"), "--plot\n--png\n");
    // Pictures are offered by their extension.
    testing::TempDir dir;
    dir.write("staff.svg", "");
    dir.write("staff.png", "");
    EXPECT_EQ(complete("vibscore show ringtone --png " + (dir.path() / "st").string()),
              (dir.path() / "staff.png").string() + "\n");
}

}  // namespace
}  // namespace vibscore
