// Numbers and names in messages, as a person writes and types them.
#include <gtest/gtest.h>

#include "common/closest_name.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"

namespace vibscore {
namespace {

TEST(NumberText, PrintsTheShortestDecimalThatReadsBackTheSame) {
    EXPECT_EQ(number_text(1000.0), "1000");
    EXPECT_EQ(number_text(0.25), "0.25");
    EXPECT_EQ(number_text(-1.0), "-1");
    EXPECT_EQ(number_text(3600000.0), "3600000");
    EXPECT_EQ(number_text(0.1), "0.1");
    EXPECT_EQ(number_text(2.0 / 3.0), "0.6666666666666666");
    EXPECT_EQ(number_text(0.0), "0");
}

TEST(RoundedText, PrintsAtMostSixDigitsWithoutTrailingZerosOrExponents) {
    EXPECT_EQ(rounded_text(3.0 / 7.0), "0.428571");
    EXPECT_EQ(rounded_text(0.2), "0.2");
    EXPECT_EQ(rounded_text(60.0 / (3.0 / 7.0), 4), "140");
    EXPECT_EQ(rounded_text(999999.0), "999999");  // the last value %g would keep fixed
    EXPECT_EQ(rounded_text(1000000.4), "1000000");
    EXPECT_EQ(rounded_text(0.0001234567), "0.000123457");
    EXPECT_EQ(rounded_text(0.00001234567), "0.0000123457");  // %g: 1.23457e-05
    EXPECT_EQ(rounded_text(-2.5), "-2.5");
    EXPECT_EQ(rounded_text(9.9999996), "10");
    EXPECT_EQ(rounded_text(0.0), "0");
}

TEST(QuotedText, ShowsControlCharactersAsEscapesSoNoneForgesALogLine) {
    EXPECT_EQ(quoted_text("org.gnome.Clocks"), "\"org.gnome.Clocks\"");
    EXPECT_EQ(quoted_text("a\n<3>forged\r"), "\"a\\x0a<3>forged\\x0d\"");
    EXPECT_EQ(quoted_text(std::string("a\0b\x7f\x1f ", 6)), "\"a\\x00b\\x7f\\x1f \"");
    EXPECT_EQ(quoted_text(""), "\"\"");
}

TEST(QuotedText, ShowsEightyBytesAndTheSizeOfMore) {
    EXPECT_EQ(quoted_text(std::string(80, 'x')), "\"" + std::string(80, 'x') + "\"");
    EXPECT_EQ(quoted_text(std::string(81, 'x')), "\"" + std::string(80, 'x') + "\"... (81 bytes)");
}

TEST(QuotedText, CutsBeforeAUtf8CharacterNotInsideIt) {
    // 79 bytes, then a two-byte character across the 80th: it is left out whole.
    const std::string text = std::string(79, 'x') + "\xc3\xa9" + "yz";
    EXPECT_EQ(quoted_text(text), "\"" + std::string(79, 'x') + "\"... (83 bytes)");
    // Ending exactly at the 80th byte, it is kept.
    const std::string fits = std::string(78, 'x') + "\xc3\xa9" + "yz";
    EXPECT_EQ(quoted_text(fits), "\"" + std::string(78, 'x') + "\xc3\xa9\"... (82 bytes)");
}

TEST(QuotedText, AMegabyteOfTextWithANulShowsEightyEscapedBytes) {
    std::string text(100'000, 'v');
    text[3] = '\0';
    const std::string quoted = quoted_text(text);
    EXPECT_EQ(quoted, "\"vvv\\x00" + std::string(76, 'v') + "\"... (100000 bytes)");
    EXPECT_EQ(quoted.find('\0'), std::string::npos);
}

TEST(QuotedText, ShownTextIsTheSameWithoutTheQuotes) {
    EXPECT_EQ(shown_text("sim"), "sim");
    EXPECT_EQ(shown_text(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(shown_text(std::string(81, 'k')), std::string(80, 'k') + "... (81 bytes)");
}

TEST(ClosestName, FindsTheNameATypoWasMeantToBe) {
    const std::vector<std::string> verbs{"list", "play", "stop", "compose", "check"};
    EXPECT_EQ(closest_name("lsit", verbs), "list");  // two letters swapped
    EXPECT_EQ(closest_name("plya", verbs), "play");
    EXPECT_EQ(closest_name("compse", verbs), "compose");  // one left out
    EXPECT_EQ(closest_name("led-vibrater", {"led-vibrator", "sim"}), "led-vibrator");
}

TEST(ClosestName, OffersNothingWhenNoNameIsClose) {
    EXPECT_EQ(closest_name("frobnicate", {"list", "play"}), std::nullopt);
    EXPECT_EQ(closest_name("x", {}), std::nullopt);
}

}  // namespace
}  // namespace vibscore
