// `vibscore show FILE`: the real binary's output, as a user sees it.
#include <gtest/gtest.h>

#include <sstream>

#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::required_env;
using testing::run_command;

std::string shipped(const std::string& name) {
    return required_env("VIBSCORE_CLEFS") + "/" + name;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

// Terminal columns of UTF-8 text whose characters are one column each.
std::size_t columns(const std::string& line) {
    std::size_t count = 0;
    for (const char c : line) {
        count += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
    }
    return count;
}

TEST(Show, DrawsTheTitleAndTheStaffOfAFile) {
    const auto shown =
        run_command({required_env("VIBSCORE"), "show", shipped("notification-message.score.xml")});
    ASSERT_EQ(shown.exit_code, 0) << shown.err;
    const auto lines = lines_of(shown.out);
    ASSERT_GE(lines.size(), 12u);
    EXPECT_EQ(lines[0], "notification: message");
    EXPECT_EQ(lines[2], " [lra 2]");  // 8th + 8th rest + quarter: fewer than four beats
    // Lines 4 to 9 are strings 6 (top) to 1: the 8th (number 6) on string 4, the quarter (8)
    // on string 5, the rest across the two middle strings.
    EXPECT_NE(lines[6].find("│6━"), std::string::npos) << lines[6];
    EXPECT_NE(lines[5].find("8━"), std::string::npos) << lines[5];
    EXPECT_NE(lines[6].find("▬"), std::string::npos) << lines[6];
    EXPECT_NE(lines[7].find("▬"), std::string::npos) << lines[7];
    EXPECT_NE(lines[3].find(">"), std::string::npos);  // the decrescendo
    EXPECT_NE(lines[11].find("8   8   4"), std::string::npos) << lines[11];
    EXPECT_EQ(shown.out.find('\x1b'), std::string::npos);  // not a terminal: plain
}

TEST(Show, BreaksALongScoreIntoSystemsThatFitTheWidth) {
    const auto shown = run_command(
        {required_env("VIBSCORE"), "show", shipped("ode-to-joy.score.xml"), "--width", "40"});
    ASSERT_EQ(shown.exit_code, 0) << shown.err;
    int systems = 0;
    for (const auto& line : lines_of(shown.out)) {
        EXPECT_LE(columns(line), 40u) << line;
        systems += line.find("[shaker 4]") != std::string::npos ? 1 : 0;
    }
    EXPECT_GE(systems, 8);  // 16 bars, at most two in 40 columns
}

TEST(Show, ColoursOnRequestWithTheClefBoxByBeatCount) {
    const auto shown = run_command(
        {required_env("VIBSCORE"), "show", shipped("notification-message.score.xml"), "--colour"});
    ASSERT_EQ(shown.exit_code, 0) << shown.err;
    EXPECT_NE(shown.out.find("\x1b[30;46m[lra 2]"), std::string::npos);  // cyan: fewer than 4
    const auto four =
        run_command({required_env("VIBSCORE"), "show", shipped("ringtone.score.xml"), "--color"});
    EXPECT_NE(four.out.find("\x1b[30;47m[lra 4]"), std::string::npos);  // white: exactly 4
}

TEST(Show, ABadFileIsReportedWithItsPlace) {
    testing::TempDir dir;
    const auto bad = dir.write("bad.xml",
                               "<VibScore><Bar clef=\"x\"><Note length=\"9th\"/>"
                               "</Bar></VibScore>");
    const auto shown = run_command({required_env("VIBSCORE"), "show", bad.string()});
    EXPECT_EQ(shown.exit_code, 1);
    EXPECT_NE(shown.err.find("bad.xml:1:"), std::string::npos) << shown.err;
    EXPECT_NE(shown.err.find("9th"), std::string::npos) << shown.err;
    const auto usage = run_command({required_env("VIBSCORE"), "show"});
    EXPECT_EQ(usage.exit_code, 2);
}

TEST(Edit, NeedsATerminal) {
    const auto edit = run_command({required_env("VIBSCORE"), "edit", "x.score.xml"});
    EXPECT_EQ(edit.exit_code, 1);
    EXPECT_NE(edit.err.find("needs a terminal"), std::string::npos) << edit.err;
}

}  // namespace
}  // namespace vibscore
