#include <gtest/gtest.h>

#include "score/length.hpp"

namespace vibscore {
namespace {

TEST(Length, EveryDocumentSpellingHasTheThesisDuration) {
    const std::pair<const char*, double> expected[] = {
        {"whole", 4},   {"half_dot", 3},   {"half", 2},  {"quarter_dot", 1.5},
        {"quarter", 1}, {"8th_dot", 0.75}, {"8th", 0.5}, {"16th_dot", 0.375},
        {"16th", 0.25}, {"32th", 0.125},
    };
    for (const auto& [name, quarters] : expected) {
        const auto length = parse_length(name);
        ASSERT_TRUE(length.has_value()) << name;
        EXPECT_EQ(beats(*length), quarters) << name;
        EXPECT_EQ(to_string(*length), name);
    }
}

TEST(Length, RejectsSpellingsOutsideTheTen) {
    for (const char* name : {"", "Quarter", "32nd", "8", "eighth", "quarter ", "64th"}) {
        EXPECT_FALSE(parse_length(name).has_value()) << name;
    }
}

}  // namespace
}  // namespace vibscore
