// What a clef asks that a declared actuator cannot give (render::clef_warnings), and the client's
// `vibscore clef fit` and `vibscore check CLEF --actuator`, run as the real vibscore binary.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "daemon/render/fitting/clef_check.hpp"
#include "daemon/render/fitting/clef_fit.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "tests/support/example_actuators.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using testing::required_env;
using testing::run_command;
using testing::TempDir;

std::filesystem::path shipped(const std::string& name) {
    return std::filesystem::path(required_env("VIBSCORE_CLEFS")) / name;
}

Clef sine_clef(std::vector<double> frequencies, std::vector<double> numbers = {0.5, 1.0}) {
    Clef clef;
    clef.tempo = 0.2;
    clef.numbers = std::move(numbers);
    for (const double f : frequencies) {
        clef.strings.push_back({f, {}});
    }
    return clef;
}

std::size_t count_with(const std::vector<std::string>& warnings, const std::string& text) {
    return static_cast<std::size_t>(
        std::count_if(warnings.begin(), warnings.end(),
                      [&](const std::string& w) { return w.find(text) != std::string::npos; }));
}

TEST(ClefWarnings, NameEachLraPhoneStringFullDriveLeavesShortAndEachPairTooClose) {
    const auto warnings =
        render::clef_warnings(load_clef_file(shipped("lra-phone.clef.xml")), example_lra());
    // 170 Hz is the one string within the band where full drive gives strength 1.
    EXPECT_EQ(count_with(warnings, "full drive gives strength"), 5u);
    EXPECT_THAT(warnings, Contains(HasSubstr("string 6 (235 Hz): full drive gives strength 0.12, "
                                             "less than the clef's strongest number (1)")));
    EXPECT_THAT(warnings, Not(Contains(HasSubstr("string 2 (170 Hz): full drive"))));
    EXPECT_EQ(count_with(warnings, "closer than a person tells apart"), 5u);
    EXPECT_THAT(warnings, Contains(HasSubstr("strings 1 and 2 (155 Hz, 170 Hz): frequency ratio "
                                             "1.10")));
    EXPECT_THAT(warnings, Contains(HasSubstr("number 9 (strength 1): out of reach on strings 1, "
                                             "3, 4, 5, 6")));
}

TEST(ClefWarnings, SayAnErmHasNoPitchInOneLine) {
    const auto warnings =
        render::clef_warnings(load_clef_file(shipped("lra-phone.clef.xml")), example_erm());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("strings 1-6 (155 Hz to 235 Hz): an ERM has no pitch"));
}

TEST(ClefWarnings, AcceptAStringAtTheBandsEdgeAndWarnJustOutside) {
    const auto lra = example_lra();
    const auto band = render::full_strength_band(lra, 1.0);
    ASSERT_TRUE(band);
    EXPECT_THAT(render::clef_warnings(sine_clef({band->high_hz * (1 - 1e-6)}), lra), IsEmpty());
    EXPECT_EQ(count_with(render::clef_warnings(sine_clef({band->high_hz * (1 + 1e-6)}), lra),
                         "full drive gives strength"),
              1u);
}

TEST(ClefWarnings, AcceptStringsExactlyTheDistinctRatioApartAndWarnCloser) {
    const auto wide = example_lra(175.0, 1.0);
    EXPECT_THAT(render::clef_warnings(sine_clef({100, 120}, {0.5}), wide), IsEmpty());
    EXPECT_EQ(
        count_with(render::clef_warnings(sine_clef({100, 119.9}, {0.5}), wide), "strings 1 and 2"),
        1u);
}

TEST(ClefWarnings, NameANumberBeyondFullDriveOnAShapeClef) {
    Clef clef;
    clef.type = ClefType::line;
    clef.tempo = 0.2;
    clef.numbers = {1.0 / 0.7, 1.5};
    clef.strings = {{0.0, {{0.0, 1.0}, {1.0, 1.0}}}};
    const auto warnings = render::clef_warnings(clef, example_erm());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_THAT(warnings[0], HasSubstr("number 2 (strength 1.5): out of reach, full drive gives "
                                       "1.43"));
}

TEST(ClefWarnings, NameWigglesAndPulsesTheActuatorCannotFollow) {
    Clef clef;
    clef.type = ClefType::line;
    clef.tempo = 0.2;
    clef.numbers = {1.0};
    clef.strings = {{0.0, {{0.0, 0.0}, {0.025, 1.0}, {0.05, 0.0}, {1.0, 0.0}}}};
    EXPECT_THAT(render::clef_warnings(clef, example_erm()),
                Contains(HasSubstr("string 1: a 5 ms rise or fall, faster than the ERM follows")));
    const auto rough =
        render::clef_warnings(load_clef_file(shipped("erm-rough.clef.xml")), example_erm());
    EXPECT_THAT(rough, Contains(HasSubstr("string 6: 10 ms pulses reach strength 0.32 of 1")));
    EXPECT_THAT(rough, Not(Contains(HasSubstr("string 1:"))));  // 60 ms pulses: reached
}

TEST(ClefWarnings, AreNoneForEveryShippedSineClefOnceFitted) {
    for (const auto& d : {example_erm(), example_lra()}) {
        for (const char* name : {"lra-phone", "lra-phone-140bpm", "shaker-sine-high",
                                 "shaker-sine-linear", "shaker-sine-low"}) {
            const auto fit =
                render::fit_clef(load_clef_file(shipped(std::string(name) + ".clef.xml")), d);
            EXPECT_THAT(render::clef_warnings(fit.clef, d), IsEmpty()) << name;
        }
    }
}

// --- the client ---

std::string vibscore() {
    return required_env("VIBSCORE");
}

const char* const kLraBoard =
    "[sim]\n[actuator]\nkind = lra\nresonance-hz = 175\nq = 15\nrated-drive = 0.7\n"
    "brake = reverse\n";

TEST(ClientClefFit, WritesTheFittedClefAndSaysWhatChanged) {
    TempDir dir;
    const auto board = dir.write("board.conf", kLraBoard).string();
    const auto out = dir.path() / "fitted.clef.xml";
    const auto result = run_command({vibscore(), "clef", "fit", shipped("lra-phone.clef.xml"),
                                     "--actuator", board, "-o", out.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.out, IsEmpty());
    EXPECT_THAT(result.err, HasSubstr("fitted to lra: resonance 175 Hz"));
    EXPECT_THAT(result.err, HasSubstr("too narrow for 6 strings"));
    const Clef fitted = load_clef_file(out);
    EXPECT_EQ(fitted,
              render::fit_clef(load_clef_file(shipped("lra-phone.clef.xml")), example_lra()).clef);
    EXPECT_THAT(testing::read_file(out), HasSubstr("<!-- Fitted by vibscore clef fit from"));
    // What it wrote passes the check with no warning for that actuator.
    const auto check = run_command({vibscore(), "check", out.string(), "--actuator", board});
    EXPECT_EQ(check.exit_code, 0) << check.err;
    EXPECT_THAT(check.out, HasSubstr("0 warnings for the actuator"));
}

TEST(ClientClefFit, FindsAShippedClefByNameAndWritesToStandardOutput) {
    TempDir dir;
    const auto board = dir.write("board.conf", kLraBoard).string();
    const auto result = run_command({vibscore(), "clef", "fit", "soft-shapes", "--actuator", board,
                                     "--clefs", required_env("VIBSCORE_CLEFS")});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("<VibClef type=\"curve\""));
    EXPECT_THAT(result.err, HasSubstr("soft-shapes: fits to lra: resonance 175 Hz"));
    EXPECT_THAT(result.err, HasSubstr("as written"));
}

TEST(ClientClefFit, NamesTheFileAndLineOfABadClefOrActuator) {
    TempDir dir;
    const auto board = dir.write("board.conf", kLraBoard).string();
    const auto bad = dir.write("bad.clef.xml",
                               "<?xml version=\"1.0\"?>\n<VibClef type=\"sine\">\n"
                               "<Tempo>-1</Tempo>\n</VibClef>\n");
    const auto clef = run_command({vibscore(), "clef", "fit", bad.string(), "--actuator", board});
    EXPECT_EQ(clef.exit_code, 1);
    EXPECT_THAT(clef.err, HasSubstr(bad.string() + ":3:"));
    EXPECT_THAT(clef.err, HasSubstr("\"-1\""));
    const auto missing =
        run_command({vibscore(), "clef", "fit", "no-such-clef", "--actuator", board});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_THAT(missing.err, HasSubstr("no-such-clef: no such clef file, and no clef"));
    const auto board_bad = dir.write("bad.conf", "[actuator]\nkind = lra\nq = 0.5\n").string();
    const auto actuator = run_command(
        {vibscore(), "clef", "fit", shipped("lra-phone.clef.xml"), "--actuator", board_bad});
    EXPECT_EQ(actuator.exit_code, 2);
    EXPECT_THAT(actuator.err, HasSubstr(board_bad + ":3:"));
    const auto output =
        run_command({vibscore(), "clef", "fit", shipped("lra-phone.clef.xml"), "--actuator", board,
                     "-o", (dir.path() / "no" / "dir.xml").string()});
    EXPECT_EQ(output.exit_code, 1);
    EXPECT_THAT(output.err, HasSubstr("cannot write"));
}

TEST(ClientClefFit, HasHelp) {
    const auto help = run_command({vibscore(), "clef", "fit", "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_THAT(help.out, AllOf(HasSubstr("--actuator"), HasSubstr("-o,--output"),
                                HasSubstr("docs/clefs.md")));
}

TEST(ClientCheck, WarnsWhatAClefAsksOfTheActuatorWithASummaryAndSucceeds) {
    TempDir dir;
    const auto board = dir.write("board.conf", kLraBoard).string();
    const auto result = run_command(
        {vibscore(), "check", shipped("lra-phone.clef.xml").string(), "--actuator", board});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.err, HasSubstr("lra-phone.clef.xml: warning: string 6 (235 Hz): full "
                                      "drive gives strength 0.12"));
    EXPECT_THAT(result.out, HasSubstr("19 warnings for the actuator (lra: resonance 175 Hz"));
}

}  // namespace
}  // namespace vibscore
