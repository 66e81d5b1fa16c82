// The one INI reader (common/ini_reader.hpp) at its edges, and the client's --actuator FILE and
// the daemon's vibscored.conf reading one file the same way.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "actuator/declaration.hpp"
#include "client/actuator_option.hpp"
#include "common/ini_reader.hpp"
#include "daemon/config.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string ini_error(const std::string& text) {
    try {
        read_ini(text, "f.conf");
    } catch (const IniError& error) {
        return error.what();
    }
    return "<no error>";
}

TEST(IniReader, GivesHeadersAndSettingsInFileOrderWithTheirLines) {
    const auto lines =
        read_ini("# a comment\n[sim]\n  model =  erm \n\n[actuator]\nkind=lra\n", "f.conf");
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_TRUE(lines[0].is_header());
    EXPECT_EQ(lines[0].section, "sim");
    EXPECT_EQ(lines[0].where, "f.conf:2");
    EXPECT_EQ(lines[1].key, "model");
    EXPECT_EQ(lines[1].value, "erm");
    EXPECT_EQ(lines[1].where, "f.conf:3");
    EXPECT_EQ(lines[3].section, "actuator");
    EXPECT_EQ(lines[3].key, "kind");
    EXPECT_EQ(lines[3].value, "lra");
}

TEST(IniReader, ACommentAfterAValueNeedsABlankBeforeIt) {
    // Last allowed: one blank (a space or a tab) before the mark.
    EXPECT_EQ(read_ini("[a]\nk = lra #x\n", "f.conf").at(1).value, "lra");
    EXPECT_EQ(read_ini("[a]\nk = lra\t;x\n", "f.conf").at(1).value, "lra");
    // First refused: the mark right after the value.
    EXPECT_EQ(ini_error("[a]\nk = lra#x\n"),
              "f.conf:2: k = \"lra#x\" holds '#', which starts a comment only at the start of a "
              "line or after a space; a value cannot contain it");
    EXPECT_THAT(ini_error("[a]\nk = lra;x\n"), StartsWith("f.conf:2: k = \"lra;x\" holds ';'"));
}

TEST(IniReader, AMalformedHeaderIsAnErrorNotASkippedSection) {
    // Last allowed: a one-character name.
    EXPECT_EQ(read_ini("[a]\n", "f.conf").at(0).section, "a");
    EXPECT_EQ(ini_error("[]\n"), "f.conf:1: malformed section header \"[]\"");
    EXPECT_EQ(ini_error("[actuator\nkind = lra\n"),
              "f.conf:1: malformed section header \"[actuator\"");
    EXPECT_EQ(ini_error("[actuator]x\n"), "f.conf:1: malformed section header \"[actuator]x\"");
}

TEST(IniReader, ALineThatIsNotKeyEqualsValueIsAnError) {
    EXPECT_EQ(ini_error("[a]\nkind lra\n"),
              "f.conf:2: expected \"key = value\", found \"kind lra\"");
    EXPECT_EQ(ini_error("[a]\n= 3\n"), "f.conf:2: expected \"key = value\", found \"= 3\"");
    EXPECT_EQ(ini_error("k = v\n"), "f.conf:1: \"k\" is outside any [section]");
    // An empty value is the section's reader's to refuse or allow.
    EXPECT_EQ(read_ini("[a]\nk =\n", "f.conf").at(1).value, "");
}

TEST(IniReader, AKeySetTwiceInASectionIsAnErrorEvenAcrossRepeatedHeaders) {
    EXPECT_EQ(ini_error("[a]\nk = 1\n[b]\nk = 2\n[a]\nk = 3\n"),
              "f.conf:6: k = \"3\" sets [a] k again (f.conf:2 set it to \"1\"); keep one of them");
    EXPECT_EQ(read_ini("[a]\nk = 1\n[b]\nk = 2\n", "f.conf").size(), 4u);
}

TEST(IniReader, AValueInAnErrorIsQuotedAtMostEightyBytes) {
    const std::string error = ini_error("[a]\nk = " + std::string(200, 'v') + "#\n");
    EXPECT_THAT(error, HasSubstr("\"" + std::string(80, 'v') + "\"... (201 bytes)"));
}

// The same text through both programs' paths: the daemon's parse_config and the client's
// load_actuator (render --actuator, check --actuator).
struct BothReadings {
    std::string daemon;  // the declaration described, or the error
    std::string client;
};

BothReadings read_both(const std::string& text) {
    vibscore::testing::TempDir dir;
    const auto path = dir.path() / "board.conf";
    std::ofstream(path) << text;
    BothReadings readings;
    try {
        const auto config = daemon::load_config(path);
        readings.daemon = config.actuator ? actuator::describe(*config.actuator) : "none";
    } catch (const daemon::ConfigError& error) {
        readings.daemon = error.what();
    }
    try {
        readings.client = actuator::describe(client::load_actuator(path.string()));
    } catch (const std::runtime_error& error) {
        readings.client = error.what();
    }
    // The file's path starts each message; compare what follows it.
    for (std::string* reading : {&readings.daemon, &readings.client}) {
        if (reading->rfind(path.string(), 0) == 0) {
            reading->replace(0, path.string().size(), "FILE");
        }
    }
    return readings;
}

TEST(IniReader, TheClientAndTheDaemonReadOneFileTheSameWay) {
    for (const std::string& text : {
             std::string("[actuator]\nkind = lra  # the board's vibra\nq = 20 ; sharp\n"),
             std::string("[actuator]\nkind = lra#x\n"),
             std::string("[actuator\nkind = lra\n"),
             std::string("[daemon]\ndriver = sim\n[sim]\nmodel = erm#x\n[actuator]\nkind = erm\n"),
             std::string("[actuator]\nkind = erm\nrated-drive = 0.7\nrated-drive = 0.8\n"),
             std::string("[actuator]\nkind = erm\nq = 15\n"),
             std::string("[actuator]\nkind = lra\n[sim]\nmodel = lra\n[actuator]\nq = 3\n"),
         }) {
        const auto readings = read_both(text);
        EXPECT_EQ(readings.daemon, readings.client) << text;
    }
    // And what they read: the comment dropped, the value kept.
    EXPECT_EQ(read_both("[actuator]\nkind = lra  # x\nq = 20 ; sharp\n").client,
              "lra: resonance 175 Hz, q 20 (envelope 36.4 ms), rated-drive 1, brake none, "
              "compensation on");
    EXPECT_THAT(read_both("[actuator]\nkind = lra#x\n").client,
                StartsWith("FILE:2: kind = \"lra#x\" holds '#'"));
    EXPECT_THAT(read_both("[actuator\nkind = lra\n").client,
                StartsWith("FILE:1: malformed section header"));
}

// Every number a setting holds is read by one rule: the whole text, finite, decimal.
TEST(IniNumber, TheWholeTextAFiniteDecimalAndNothingElse) {
    EXPECT_EQ(ini_number("1"), 1.0);
    EXPECT_EQ(ini_number("0.25"), 0.25);
    EXPECT_EQ(ini_number("-3"), -3.0);
    EXPECT_EQ(ini_number("1e308"), 1e308);        // the largest power of ten a double holds
    EXPECT_EQ(ini_number("4.9e-324"), 4.9e-324);  // a subnormal is a number; ranges judge it
    for (const char* refused :
         {"", " 1", "1 ", "+1", "0x10", "1.5abc", "inf", "nan", "1e309", "-1e309", "one"}) {
        EXPECT_EQ(ini_number(refused), std::nullopt) << '"' << refused << '"';
    }
}

}  // namespace
}  // namespace vibscore
