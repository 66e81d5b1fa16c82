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
using ::testing::Not;
using testing::required_env;
using testing::run_command;
using testing::TempDir;

std::string vibscore() {
    return required_env("VIBSCORE");
}
std::filesystem::path shipped(const std::string& name) {
    return std::filesystem::path(required_env("VIBSCORE_CLEFS")) / name;
}

// With no daemon to ask: the clef rule's registry step finds nothing.
constexpr const char* kNoBus = "DBUS_SYSTEM_BUS_ADDRESS=unix:path=/nonexistent/bus";

testing::CommandResult convert(std::vector<std::string> args) {
    args.insert(args.begin(), {"/usr/bin/env", kNoBus, vibscore(), "convert"});
    return run_command(args);
}

testing::CommandResult check(std::vector<std::string> args) {
    args.insert(args.begin(), {"/usr/bin/env", kNoBus, vibscore(), "check"});
    return run_command(args);
}

std::string href_in(const std::filesystem::path& score) {
    return read_score(testing::read_file(score), score.string()).score.clefs.at(0).href;
}

// Steps of 200 ms: on lra-phone's grid (a quarter is 0.2 s), so no copy of the clef is needed.
constexpr const char* kPulse = R"({"timings": [0, 200, 200, 200]})";

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
    const auto by_name = convert(
        {envelope.string(), (dir.path() / "e.score.xml").string(), "--clef", "shaker-sine-linear"});
    EXPECT_EQ(by_name.exit_code, 0) << by_name.err;
}

TEST(ConvertCli, UsageErrorsExitTwoAndBadFilesNameWhereTheyGoWrong) {
    TempDir dir;
    const auto score = shipped("create.score.xml").string();
    const auto unknown = convert({score, (dir.path() / "x.wav").string()});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_THAT(unknown.err, HasSubstr("cannot tell the format of"));
    // Each side offers only the formats it takes: RTTTL is read, not written; the envelope
    // form is written, and read as android-xml.
    EXPECT_THAT(unknown.err, HasSubstr("give --to (score, ahap, android-json, android-xml, "
                                       "android-envelope, midi)\n"));
    const auto unread = convert({(dir.path() / "x.txt").string(), score});
    EXPECT_EQ(unread.exit_code, 2);
    EXPECT_THAT(unread.err,
                HasSubstr("give --from (score, ahap, android-json, android-xml, rtttl, midi)\n"));
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

// Issue 25: the first convert a newcomer tries, from the build tree, with nothing installed and
// no daemon; and with the clef named. The clef is found by the rule check follows: here the
// shipped clefs of the build tree's source.
TEST(ConvertCli, ImportsWithoutFlagsOntoTheShippedLraPhoneFromABuildTree) {
    const auto tune = std::filesystem::path(required_env("VIBSCORE_CLEFS")) / ".." / "examples" /
                      "rtttl" / "fur-elise.rtttl";
    for (const auto& flags : std::vector<std::vector<std::string>>{{}, {"--clef", "lra-phone"}}) {
        TempDir dir;
        const auto out = dir.path() / "fur-elise.score.xml";
        std::vector<std::string> args{tune.string(), out.string()};
        args.insert(args.end(), flags.begin(), flags.end());
        const auto result = convert(args);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_THAT(result.out, HasSubstr(" on clef lra-phone from "));
        EXPECT_THAT(result.out, HasSubstr("lra-phone.clef.xml\n"));
        const auto checked = check({out.string()});
        EXPECT_EQ(checked.exit_code, 0) << checked.out << checked.err;
    }
}

// An import that needs no copy of its clef names the clef as the clef rule finds it again: by
// registry name, or by its file's path relative to the score; never by an absolute path.
TEST(ConvertCli, AnImportNamesItsClefByRegistryNameOrByAPathRelativeToTheScore) {
    TempDir dir;
    const auto pulse = dir.write("pulse.json", kPulse);
    std::filesystem::create_directories(dir.path() / "scores");
    std::filesystem::create_directories(dir.path() / "clefs");
    const auto mine = dir.path() / "clefs" / "mine.clef.xml";
    std::filesystem::copy_file(shipped("lra-phone.clef.xml"), mine);

    const auto by_name = dir.path() / "scores" / "by-name.score.xml";
    ASSERT_EQ(convert({pulse.string(), by_name.string()}).exit_code, 0);
    EXPECT_EQ(href_in(by_name), "lra-phone.clef.xml");

    const auto by_file = dir.path() / "scores" / "by-file.score.xml";
    const auto from_file = convert({pulse.string(), by_file.string(), "--clef", mine.string()});
    ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
    EXPECT_EQ(href_in(by_file), "../clefs/mine.clef.xml");
    EXPECT_EQ(check({by_file.string()}).exit_code, 0);

    // A clef of one's own, found in a --clefs folder by its name: check finds it the same way.
    const auto own = dir.path() / "scores" / "own.score.xml";
    const auto clefs = (dir.path() / "clefs").string();
    const auto from_folder =
        convert({pulse.string(), own.string(), "--clefs", clefs, "--clef", "mine"});
    ASSERT_EQ(from_folder.exit_code, 0) << from_folder.err;
    EXPECT_THAT(from_folder.out, HasSubstr(" on clef mine from " + mine.string() + "\n"));
    EXPECT_EQ(href_in(own), "mine.clef.xml");
    EXPECT_EQ(check({"--clefs", clefs, own.string()}).exit_code, 0);
    EXPECT_EQ(check({own.string()}).exit_code, 1);  // "mine" is nowhere else

    const auto nowhere =
        convert({pulse.string(), (dir.path() / "n.score.xml").string(), "--clef", "no-such"});
    EXPECT_EQ(nowhere.exit_code, 1);
    EXPECT_THAT(nowhere.err, HasSubstr("no clef \"no-such\" in "));
}

// A clef file of that name beside the score would be the clef the score plays (rule 1), not the
// one it was converted onto: refused, and nothing written. The same clef there is fine.
TEST(ConvertCli, RefusesToNameAClefThatAnotherClefFileBesideTheScoreWouldShadow) {
    TempDir dir;
    const auto pulse = dir.write("pulse.json", kPulse);
    std::filesystem::copy_file(shipped("erm-phone.clef.xml"), dir.path() / "lra-phone.clef.xml");
    const auto out = dir.path() / "pulse.score.xml";
    const auto refused = convert({pulse.string(), out.string()});
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.err, HasSubstr((dir.path() / "lra-phone.clef.xml").string() +
                                       " exists with another clef"));
    EXPECT_FALSE(std::filesystem::exists(out));
    std::filesystem::remove(dir.path() / "lra-phone.clef.xml");
    std::filesystem::copy_file(shipped("lra-phone.clef.xml"), dir.path() / "lra-phone.clef.xml");
    EXPECT_EQ(convert({pulse.string(), out.string()}).exit_code, 0);

    // The same for the copies at the piece's tempi: every one is checked before any is written.
    TempDir other;
    const auto tune = other.write("slowing.rtttl", "slowing:d=4,o=5,b=120:c,d,b=60,e");
    std::filesystem::copy_file(shipped("erm-phone.clef.xml"),
                               other.path() / "lra-phone-60bpm.clef.xml");
    const auto copies = convert({tune.string(), (other.path() / "s.score.xml").string()});
    EXPECT_EQ(copies.exit_code, 1);
    EXPECT_THAT(copies.err, HasSubstr("lra-phone-60bpm.clef.xml exists with another clef"));
    EXPECT_EQ(testing::file_names(other.path()),
              (std::vector<std::string>{"lra-phone-60bpm.clef.xml", "slowing.rtttl"}));
}

// The score a reader would refuse for its size (1 MiB) is not written, nor its clef's copy.
TEST(ConvertCli, AScoreTooLargeForADocumentIsRefusedAndNothingIsWritten) {
    TempDir dir;
    std::string tune = "big:d=32,o=5,b=150:c";
    for (int i = 1; i < 30'000; ++i) {
        tune += i % 2 ? ",e" : ",c";
    }
    const auto file = dir.write("big.rtttl", tune);
    const auto refused = convert({file.string(), (dir.path() / "big.score.xml").string()});
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_THAT(refused.err, HasSubstr("-byte limit for a document; nothing written"));
    EXPECT_EQ(testing::file_names(dir.path()), std::vector<std::string>{"big.rtttl"});
}

// A vibscore in a meson build tree finds the shipped clefs in its source tree (named in
// meson-info/meson-info.json); an installed one looks in the installed folder.
TEST(ConvertCli, AVibscoreInABuildTreeFindsItsSourceTreesClefsAndAnInstalledOneDoesNot) {
    TempDir dir;
    const auto source = dir.path() / "src";
    std::filesystem::create_directories(source / "clefs");
    std::filesystem::copy_file(shipped("lra-phone.clef.xml"),
                               source / "clefs" / "lra-phone.clef.xml");
    std::filesystem::create_directories(dir.path() / "build" / "meson-info");
    std::filesystem::create_directories(dir.path() / "build" / "client");
    dir.write("build/meson-info/meson-info.json",
              R"({"directories": {"source": ")" + source.string() + R"(", "build": "x"}})");
    const auto built = dir.path() / "build" / "client" / "vibscore";
    std::filesystem::copy_file(vibscore(), built);
    std::filesystem::create_directories(dir.path() / "usr" / "bin");
    const auto installed = dir.path() / "usr" / "bin" / "vibscore";
    std::filesystem::copy_file(vibscore(), installed);
    const auto pulse = dir.write("pulse.json", kPulse);

    const auto from_build = run_command({"/usr/bin/env", kNoBus, built.string(), "convert",
                                         pulse.string(), (dir.path() / "a.score.xml").string()});
    EXPECT_EQ(from_build.exit_code, 0) << from_build.err;
    EXPECT_THAT(from_build.out,
                HasSubstr("from " + (source / "clefs" / "lra-phone.clef.xml").string()));
    const auto from_install = run_command({"/usr/bin/env", kNoBus, installed.string(), "convert",
                                           pulse.string(), (dir.path() / "b.score.xml").string()});
    EXPECT_THAT(from_install.out + from_install.err, HasSubstr("share/vibscore/clefs"));
    EXPECT_THAT(from_install.out + from_install.err, Not(HasSubstr(source.string())));
}

// What Apple's parser takes and JSON forbids is read, and convert says so, file:line:column.
TEST(ConvertCli, ImportsAnAhapWithATrailingCommaAndSaysWhereItWas) {
    TempDir dir;
    const auto file = dir.write("tap.ahap",
                                "{\"Pattern\": [\n  {\"Event\": {\"Time\": 0, "
                                "\"EventType\": \"HapticTransient\"}},\n]}");
    const auto result = convert({file.string(), (dir.path() / "tap.score.xml").string()});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err, file.string() +
                              ":2:57: warning: a trailing comma, which JSON does not allow; "
                              "Apple's parser (and Apple's own sample files) take it, and so does "
                              "vibscore\n");
}

// Issue 27: 37 bytes whose delta time claims years took vibscore convert to 13.6 GB and past a
// minute; refused at the byte that claims them, and nothing written.
TEST(ConvertCli, AMidiFileOfAFewBytesThatClaimsYearsIsRefusedAtItsByte) {
    TempDir dir;
    const std::string header("MThd\0\0\0\x06\0\0\0\x01\0\x01", 14);
    const std::string events("\x00\x90\x3C\x40\xFF\xFF\xFF\x7F\x80\x3C\x40\x00\xFF\x2F\x00", 15);
    const auto file =
        dir.write("years.mid", header + "MTrk" + std::string("\0\0\0\x0F", 4) + events);
    ASSERT_EQ(std::filesystem::file_size(file), 37u);
    const auto out = dir.path() / "years.score.xml";
    const auto result =
        convert({file.string(), out.string(), "--clef", shipped("lra-phone.clef.xml").string()});
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.err, file.string() +
                              ": byte 26: a note ends 268435455 beats in; a score holds at most "
                              "10000 bars of four beats\n");
    EXPECT_FALSE(std::filesystem::exists(out));
}

// The last length allowed: an hour, at lra-phone's 0.2 s a quarter (which no binary fraction
// holds, so 4500 bars of it add up to a hair over 3600 s), converts to a score that checks.
TEST(ConvertCli, AWaveformOfExactlyAnHourConvertsToAScoreThatChecks) {
    TempDir dir;
    const auto file = dir.write("hour.json", R"({"timings": [0, 3600000]})");
    const auto out = dir.path() / "hour.score.xml";
    const auto result =
        convert({file.string(), out.string(), "--clef", shipped("lra-phone.clef.xml").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("(4500 bars, 4500 notes, 3600.000 s)"));
    const auto checked = run_command({vibscore(), "check", out.string()});
    EXPECT_EQ(checked.exit_code, 0) << checked.out << checked.err;
}

}  // namespace
}  // namespace vibscore
