// What render, check and show do with vibscored on a private bus (issue 31 rows 6-8): registry
// names as play and info take them, and `--actuator` without a file draws and checks the score
// through the clefs the daemon plays it with ([clefs] fit = auto, or a mapping), naming them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/daemon_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using ::testing::Not;

const char* const kLraSection =
    "[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nrated-drive = 0.7\nbrake = reverse\n";

testing::CommandResult vibscore(const std::vector<std::string>& args) {
    std::vector<std::string> argv{testing::required_env("VIBSCORE")};
    argv.insert(argv.end(), args.begin(), args.end());
    return testing::run_command(argv);
}

std::string shipped(const std::string& file) {
    return testing::required_env("VIBSCORE_CLEFS") + "/" + file;
}

// The response CSV `render --actuator SPEC --out` writes for touch-click.
std::string response_csv(const testing::TempDir& dir, const std::string& name,
                         const std::vector<std::string>& actuator) {
    const auto csv = dir.path() / (name + ".csv");
    std::vector<std::string> args{"render", "touch-click", "--rate", "1000", "--out", csv.string()};
    args.insert(args.end(), actuator.begin(), actuator.end());
    const auto result = vibscore(args);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return testing::read_file(csv);
}

TEST(DaemonPictures, RenderAndCheckThroughTheDaemonUseItsFittedClefsAndSaySo) {
    testing::TempDir dir;
    const auto board = dir.write("board.conf", kLraSection);
    DaemonFixture daemon{std::string(kLraSection) + "[clefs]\nfit = auto\n"};
    // The written clef: lra-phone's 235 Hz string, far off the LRA's 175 Hz.
    const auto written = response_csv(dir, "written", {"--actuator", board.string()});
    // The daemon's: lra-phone fitted to the LRA, as it plays it.
    const auto played = response_csv(dir, "played", {"--actuator"});
    EXPECT_NE(written, played);

    const auto plot = vibscore({"render", "touch-click", "--actuator", "--plot"});
    ASSERT_EQ(plot.exit_code, 0) << plot.err;
    EXPECT_THAT(plot.out,
                HasSubstr("clefs as vibscored plays them: lra-phone -> lra-phone (fitted)\n"));
    const auto offline =
        vibscore({"render", "touch-click", "--actuator", board.string(), "--plot"});
    ASSERT_EQ(offline.exit_code, 0) << offline.err;
    EXPECT_THAT(offline.out, HasSubstr("clefs as written: lra-phone\n"));

    // The pictures differ with the clefs, and each says which it used (drawn, not asserted on
    // its pixels here: the picture tests do that).
    const auto png = dir.path() / "played.png";
    const auto drawn = vibscore({"render", "touch-click", "--actuator", "--png", png.string()});
    ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
    const auto written_png = dir.path() / "written.png";
    ASSERT_EQ(vibscore({"render", "touch-click", "--actuator", board.string(), "--png",
                        written_png.string()})
                  .exit_code,
              0);
    EXPECT_NE(testing::read_file(png), testing::read_file(written_png));

    // Checked as written, 235 Hz is out of reach; as played (fitted), it is not.
    const auto check_written = vibscore({"check", "touch-click", "--actuator", board.string()});
    EXPECT_EQ(check_written.exit_code, 0) << check_written.err;
    EXPECT_THAT(check_written.err, HasSubstr("out of reach on string 6 of clef lra"));
    const auto check_played = vibscore({"check", "touch-click", "--actuator"});
    EXPECT_EQ(check_played.exit_code, 0) << check_played.err;
    EXPECT_THAT(check_played.out,
                HasSubstr("touch-click: clefs as vibscored plays them: lra-phone -> lra-phone "
                          "(fitted)"));
    EXPECT_THAT(check_played.err, Not(HasSubstr("out of reach on string 6")));
}

TEST(DaemonPictures, WithoutFittingTheDaemonsClefsAreTheWrittenOnesAndSaidSo) {
    testing::TempDir dir;
    const auto board = dir.write("board.conf", kLraSection);
    DaemonFixture daemon{kLraSection};
    EXPECT_EQ(response_csv(dir, "played", {"--actuator"}),
              response_csv(dir, "written", {"--actuator", board.string()}));
    const auto plot = vibscore({"render", "touch-click", "--actuator", "--plot"});
    ASSERT_EQ(plot.exit_code, 0) << plot.err;
    EXPECT_THAT(plot.out, HasSubstr("clefs as vibscored plays them: lra-phone (as written)\n"));
}

TEST(DaemonPictures, RenderCheckAndShowTakeRegistryNamesAndAFilePathWins) {
    testing::TempDir dir;
    DaemonFixture daemon;
    const auto render = vibscore({"render", "success", "--plot"});
    EXPECT_EQ(render.exit_code, 0) << render.err;
    const auto check = vibscore({"check", "success", "lra-phone"});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    EXPECT_THAT(check.out, HasSubstr("success: ok (score: "));
    EXPECT_THAT(check.out, HasSubstr("lra-phone: ok (clef: sine"));
    const auto show = vibscore({"show", "success", "--svg", (dir.path() / "s.svg").string()});
    EXPECT_EQ(show.exit_code, 0) << show.err;

    // A name found nowhere: said once, exit 1.
    for (const std::string verb : {"render", "check", "show"}) {
        std::vector<std::string> args{verb, "no-such-pattern"};
        if (verb == "render") {
            args.push_back("--plot");
        }
        const auto missing = vibscore(args);
        EXPECT_EQ(missing.exit_code, 1) << verb;
        EXPECT_THAT(missing.err, HasSubstr("no-such-pattern")) << verb;
        EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
        EXPECT_EQ(missing.out, "") << verb;
    }

    // A file of the same name as a registry score wins: it is read, not the registry's.
    const auto here = dir.write("success", testing::read_file(shipped("touch-click.score.xml")));
    const auto file = vibscore({"check", here.string()});
    EXPECT_EQ(file.exit_code, 0) << file.err;
    EXPECT_THAT(file.out, HasSubstr("ok (score: 1 bar, 0.050 s)"));
}

TEST(DaemonPictures, ACheckWhoseActuatorFileIsMissingSaysOnlyThat) {
    const auto result = vibscore({"check", "lra-phone", "--actuator", "no-such-board.conf"});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.out, "");
    EXPECT_EQ(result.err, "vibscore: no-such-board.conf: cannot open: No such file or directory\n");
}

// `vibscore driver` says what the sim simulates: the declared actuator, or its own model.
TEST(DriverVerb, SaysWhatTheSimSimulates) {
    {
        DaemonFixture declared{kLraSection};
        const auto result = vibscore({"driver"});
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_THAT(result.out,
                    HasSubstr("sim: simulates the declared actuator: lra: resonance 175 Hz, q 15"));
    }
    DaemonFixture undeclared;
    const auto result = vibscore({"driver"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("sim: simulates the model its [sim] section sets"));
    EXPECT_THAT(result.out, HasSubstr("no actuator being declared"));
}

}  // namespace
}  // namespace vibscore
