// The bash completion installed for vibscore, run in a real bash against a real daemon.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

    // What bash offers after `line` (the last word is the one being completed).
    std::string complete(const std::string& line) const {
        const std::filesystem::path client = testing::required_env("VIBSCORE");
        const std::string script =
            "PATH=" + client.parent_path().string() + ":$PATH; source " +
            testing::required_env("VIBSCORE_COMPLETION") + "; COMP_LINE='" + line +
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

TEST_F(Completion, OffersConvertItsOptionsFormatsAndPictureFiles) {
    EXPECT_EQ(complete("vibscore conv"), "convert\n");
    EXPECT_EQ(complete("vibscore convert --t"), "--to\n--track\n");
    EXPECT_EQ(complete("vibscore convert a.mid b.score.xml --from "),
              "ahap\nandroid-envelope\nandroid-json\nandroid-xml\nmidi\nrtttl\nscore\n");
    EXPECT_EQ(complete("vibscore convert x.ahap --to android-"),
              "android-envelope\nandroid-json\nandroid-xml\n");
    EXPECT_EQ(complete("vibscore show ringtone --s"), "--svg\n");
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
