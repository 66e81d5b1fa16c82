// Numbers and names in messages, as a person writes and types them.
#include <gtest/gtest.h>

#include "common/closest_name.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"
#include "common/trim.hpp"

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

TEST(FixedText, RoundsToItsPlacesAndDropsTrailingZeros) {
    EXPECT_EQ(fixed_text(96.64, 1), "96.6");
    EXPECT_EQ(fixed_text(96.66, 1), "96.7");
    EXPECT_EQ(fixed_text(175.0, 1), "175");
    EXPECT_EQ(fixed_text(1.204, 2), "1.2");
    EXPECT_EQ(fixed_text(0.04, 1), "0");  // the last value that rounds to nothing
    EXPECT_EQ(fixed_text(0.06, 1), "0.1");
    EXPECT_EQ(fixed_text(1000.0, 0), "1000");  // no point: no zeros of the number dropped
    EXPECT_EQ(fixed_text(1e300, 1).size(), 301u);
}

TEST(HzAndMsText, WriteATenthOfAHertzAndOfAMillisecond) {
    EXPECT_EQ(hz_text(175.0), "175 Hz");
    EXPECT_EQ(hz_text(96.625), "96.6 Hz");
    EXPECT_EQ(ms_text(0.040), "40 ms");
    EXPECT_EQ(ms_text(0.0374), "37.4 ms");
    EXPECT_EQ(ms_text(0.00004), "0 ms");
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

TEST(Trim, DropsSpacesTabsAndCarriageReturnsAtBothEndsOnly) {
    EXPECT_EQ(trim("  kind = lra \t\r"), "kind = lra");
    EXPECT_EQ(trim("\tx"), "x");
    EXPECT_EQ(trim("x\r"), "x");
    EXPECT_EQ(trim(" a \t b "), "a \t b");  // blanks inside stay
    EXPECT_EQ(trim("x"), "x");
}

TEST(Trim, OfNothingOrOnlyBlanksIsEmpty) {
    EXPECT_EQ(trim(""), "");
    EXPECT_EQ(trim(" "), "");
    EXPECT_EQ(trim(" \t\r \r"), "");
}

TEST(Trim, KeepsNewlinesAndOtherWhitespaceWhichAreNotBlanks) {
    EXPECT_EQ(trim("\nx\n"), "\nx\n");
    EXPECT_EQ(trim(" \v\fx "), "\v\fx");
}

}  // namespace
}  // namespace vibscore
