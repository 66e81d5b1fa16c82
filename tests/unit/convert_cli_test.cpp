// Runs the real vibscore binary's convert verb: what a user types, sees and gets.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;
using testing::required_env;
using testing::run_command;
using testing::TempDir;

std::string vibscore() {
    return required_env("VIBSCORE");
}
std::filesystem::path shipped(const std::string& name) {
    return std::filesystem::path(required_env("VIBSCORE_CLEFS")) / name;
}

testing::CommandResult convert(std::vector<std::string> args) {
    args.insert(args.begin(), {vibscore(), "convert"});
    return run_command(args);
}

TEST(ConvertCli, TheShippedRtttlTunesAreTheirSourcesConvertedOntoLraPhone) {
    const auto sources =
        std::filesystem::path(required_env("VIBSCORE_CLEFS")) / ".." / "examples" / "rtttl";
    int tunes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(sources)) {
        if (entry.path().extension() != ".rtttl") {
            continue;
        }
        ++tunes;
        const auto name = entry.path().stem().string();
        SCOPED_TRACE(name);
        TempDir dir;
        const auto out = dir.path() / (name + ".score.xml");
        const auto result = convert({entry.path().string(), out.string(), "--clef",
                                     shipped("lra-phone.clef.xml").string()});
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_THAT(result.out, HasSubstr("wrote " + out.string()));
        const auto fresh = read_score(testing::read_file(out), "fresh").score;
        const auto committed = load_score_file(shipped(name + ".score.xml"));
        EXPECT_EQ(fresh, committed.score) << "convert it again: see the comment atop the score";
        for (const auto& declaration : fresh.clefs) {
            EXPECT_EQ(load_clef_file(dir.path() / declaration.href),
                      load_clef_file(shipped(declaration.href)));
        }
    }
    EXPECT_EQ(tunes, 3);
}

TEST(ConvertCli, ExportsByExtensionAndImportsBackIntoScoresThatCheck) {
    TempDir dir;
    const auto score = shipped("ode-to-joy.score.xml").string();
    for (const std::string name : {"ode.ahap", "ode.json", "ode.vibration.xml", "ode.mid"}) {
        SCOPED_TRACE(name);
        const auto exported = dir.path() / name;
        const auto result = convert({score, exported.string()});
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const auto back = (dir.path() / ("back-" + name)).string() + ".score.xml";
        const auto imported =
            convert({exported.string(), back, "--clef", shipped("lra-phone.clef.xml").string()});
        ASSERT_EQ(imported.exit_code, 0) << imported.err;
        EXPECT_THAT(imported.out, HasSubstr(" notes, "));
        const auto checked = run_command({vibscore(), "check", back});
        EXPECT_EQ(checked.exit_code, 0) << checked.out << checked.err;
    }
    // --to names a format the extension does not; a shipped clef may be named without a path.
    const auto envelope = dir.path() / "ode.xml";
    ASSERT_EQ(convert({score, envelope.string(), "--to", "android-envelope"}).exit_code, 0);
    EXPECT_THAT(testing::read_file(envelope), HasSubstr("<waveform-envelope-effect"));
    const auto by_name =
        run_command({"/usr/bin/env", "VIBSCORE_CLEFDIR=" + required_env("VIBSCORE_CLEFS"),
                     vibscore(), "convert", envelope.string(),
                     (dir.path() / "e.score.xml").string(), "--clef", "shaker-sine-linear"});
    EXPECT_EQ(by_name.exit_code, 0) << by_name.err;
}

TEST(ConvertCli, UsageErrorsExitTwoAndBadFilesNameWhereTheyGoWrong) {
    TempDir dir;
    const auto score = shipped("create.score.xml").string();
    const auto unknown = convert({score, (dir.path() / "x.wav").string()});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_THAT(unknown.err, HasSubstr("cannot tell the format of"));
    const auto rtttl = convert({score, (dir.path() / "x.rtttl").string()});
    EXPECT_EQ(rtttl.exit_code, 2);
    EXPECT_THAT(rtttl.err, HasSubstr("vibscore reads rtttl but does not write it"));
    EXPECT_EQ(convert({score, "x.ahap", "--from", "ogg"}).exit_code, 2);

    const auto bad = dir.write("bad.rtttl", "tune:d=4,o=5,b=120:\nc,e,x");
    const auto failed = convert({bad.string(), (dir.path() / "bad.score.xml").string(), "--clef",
                                 shipped("lra-phone.clef.xml").string()});
    EXPECT_EQ(failed.exit_code, 1);
    EXPECT_THAT(failed.err, HasSubstr(bad.string() + ":2:5: note \"x\""));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad.score.xml"));
    const auto midi = dir.write("bad.mid", "MThd");
    const auto short_midi = convert({midi.string(), (dir.path() / "m.score.xml").string(), "--clef",
                                     shipped("lra-phone.clef.xml").string()});
    EXPECT_EQ(short_midi.exit_code, 1);
    EXPECT_THAT(short_midi.err, HasSubstr(midi.string() + ": byte "));
}

}  // namespace
}  // namespace vibscore
