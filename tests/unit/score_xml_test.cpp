#include <gtest/gtest.h>

#include "score/limits.hpp"
#include "score/score_xml.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::first_diagnostic;

const char* const kRichScore = R"(<?xml version="1.0"?>
<VibScore version="1.0">
  <Title>every symbol</Title>
  <Clef id="low" href="clefs/low.xml"/>
  <Clef id="high" href="high.xml"/>
  <Bar clef="low">
    <Note length="whole" number="1" string="1"/>
    <Note length="half_dot" number="2" string="2" dynamics="crescendo"/>
    <Note length="half" number="3" string="3" dynamics="decrescendo" legato="7"/>
    <Note length="quarter_dot" number="4" string="4" dynamics="none" legato="7"/>
    <Rest length="quarter"/>
    <Blank/>
  </Bar>
  <Bar clef="high">
    <Note length="8th_dot" number="5" string="5" portamento="2"/>
    <Note length="8th" number="6" string="6" portamento="2"/>
    <Note length="16th_dot" number="7" string="1"/>
    <Note length="16th" number="8" string="2"/>
    <Rest length="32th"/>
    <Note length="32th" number="9" string="3"/>
  </Bar>
</VibScore>
)";

TEST(ScoreXml, ReadsEveryElementAndAttributeOfTable31) {
    const Score score = read_score(kRichScore, "rich.xml").score;
    EXPECT_EQ(score.version, "1.0");
    EXPECT_EQ(score.title, "every symbol");
    ASSERT_EQ(score.clefs.size(), 2u);
    EXPECT_EQ(score.clefs[0], (ClefDeclaration{"low", "clefs/low.xml"}));
    ASSERT_EQ(score.bars.size(), 2u);
    EXPECT_EQ(score.bars[1].clef, "high");
    ASSERT_EQ(score.bars[0].symbols.size(), 6u);
    const auto& crescendo = std::get<Note>(score.bars[0].symbols[1]);
    EXPECT_EQ(crescendo.length, Length::half_dot);
    EXPECT_EQ(crescendo.number, 2);
    EXPECT_EQ(crescendo.string, 2);
    EXPECT_EQ(crescendo.dynamics, Dynamics::crescendo);
    EXPECT_EQ(std::get<Note>(score.bars[0].symbols[2]).legato, 7);
    EXPECT_EQ(std::get<Note>(score.bars[1].symbols[0]).portamento, 2);
    EXPECT_EQ(std::get<Rest>(score.bars[0].symbols[4]).length, Length::quarter);
    EXPECT_TRUE(std::holds_alternative<Blank>(score.bars[0].symbols[5]));
    EXPECT_EQ(Score::beat_count(score.bars[0]), 4 + 3 + 2 + 1.5 + 1);
}

TEST(ScoreXml, RoundTripKeepsTheModel) {
    const Score original = read_score(kRichScore, "rich.xml").score;
    const std::string written = write_score(original);
    const Score again = read_score(written, "written.xml").score;
    EXPECT_EQ(again, original);
    EXPECT_EQ(write_score(again), written);
}

TEST(ScoreXml, RoundTripEscapesMarkupInTitleAndNames) {
    Score score;
    score.title = "R&D <beta> \"quoted\"";
    score.clefs.push_back({"c", "dir with space/c&d.xml"});
    score.bars.push_back({"c", {Note{Length::quarter, 1, 1, Dynamics::none, 0, 0}}});
    EXPECT_EQ(read_score(write_score(score), "x").score, score);
}

TEST(ScoreXml, SourceMapPointsAtEachSymbol) {
    const auto parsed = read_score(kRichScore, "rich.xml");
    EXPECT_EQ(parsed.where.bars[0].line, 6);
    EXPECT_EQ(parsed.where.bars[0].column, 3);
    EXPECT_EQ(parsed.where.symbols[1][5].line, 20);
    EXPECT_EQ(parsed.where.symbols[1][5].column, 5);
    EXPECT_EQ(parsed.where.clefs[1].line, 5);
}

struct BadScore {
    const char* name;
    std::string document;
    int line;
    int column;
    const char* message_part;
};

class BadScoreTest : public ::testing::TestWithParam<BadScore> {};

TEST_P(BadScoreTest, NamesFileLineColumnAndValue) {
    const auto& bad = GetParam();
    const auto diagnostic = first_diagnostic([&] { read_score(bad.document, "bad.xml"); });
    EXPECT_EQ(diagnostic.where.file, "bad.xml");
    EXPECT_EQ(diagnostic.where.line, bad.line) << diagnostic.message;
    EXPECT_EQ(diagnostic.where.column, bad.column) << diagnostic.message;
    EXPECT_NE(diagnostic.message.find(bad.message_part), std::string::npos) << diagnostic.message;
}

std::string score_with(const std::string& note) {
    return "<VibScore version=\"1.0\">\n<Clef id=\"c\" href=\"c.xml\"/>\n<Bar clef=\"c\">\n  " +
           note + "\n</Bar>\n</VibScore>\n";
}

INSTANTIATE_TEST_SUITE_P(
    ScoreXml, BadScoreTest,
    ::testing::Values(
        BadScore{"MalformedXml", "<VibScore>\n<Bar clef=\"c\">\n</VibScore>", 3, 3,
                 "malformed XML"},
        BadScore{"WrongRoot", "<?xml version=\"1.0\"?>\n  <Score/>", 2, 3, "expected <VibScore>"},
        BadScore{"UnknownElement", score_with("<Chord length=\"quarter\"/>"), 4, 3,
                 "unknown element <Chord>"},
        BadScore{"UnknownLength", score_with("<Note length=\"9th\" number=\"1\" string=\"1\"/>"), 4,
                 3, "unknown length \"9th\""},
        BadScore{"MissingLength", score_with("<Rest/>"), 4, 3, "has no length"},
        BadScore{"UnknownAttribute",
                 score_with("<Note length=\"8th\" number=\"1\" string=\"1\" volume=\"3\"/>"), 4, 3,
                 "unknown attribute volume"},
        BadScore{"NumberNotAnInteger",
                 score_with("<Note length=\"8th\" number=\"two\" string=\"1\"/>"), 4, 3,
                 "number \"two\" is not a whole number"},
        BadScore{"NumberZero", score_with("<Note length=\"8th\" number=\"0\" string=\"1\"/>"), 4, 3,
                 "number \"0\" is out of range (1 to 9)"},
        BadScore{"StringBeyondStaff",
                 score_with("<Note length=\"8th\" number=\"1\" string=\"7\"/>"), 4, 3,
                 "string \"7\" is out of range (1 to 6)"},
        BadScore{"MissingString", score_with("<Note length=\"8th\" number=\"1\"/>"), 4, 3,
                 "has no string"},
        BadScore{"UnknownDynamics",
                 score_with("<Note length=\"8th\" number=\"1\" string=\"1\" dynamics=\"sfz\"/>"), 4,
                 3, "unknown dynamics \"sfz\""},
        BadScore{"NegativeLegato",
                 score_with("<Note length=\"8th\" number=\"1\" string=\"1\" legato=\"-1\"/>"), 4, 3,
                 "legato serial \"-1\" is out of range"},
        BadScore{"TextInBar", score_with("hello"), 3, 15, "unexpected text \"hello\""},
        BadScore{"UndeclaredClef",
                 "<VibScore>\n<Clef id=\"c\" href=\"c.xml\"/>\n<Bar clef=\"d\"/>\n</VibScore>", 3,
                 1, "uses clef \"d\", which no <Clef> declares"},
        BadScore{"BarWithoutClef", "<VibScore>\n<Clef id=\"c\" href=\"c.xml\"/>\n<Bar/></VibScore>",
                 3, 1, "<Bar> has no clef"},
        BadScore{"DuplicateClefId",
                 "<VibScore>\n<Clef id=\"c\" href=\"a.xml\"/>\n<Clef id=\"c\" href=\"b.xml\"/>\n"
                 "</VibScore>",
                 3, 1, "declared twice"},
        BadScore{"ClefWithoutHref", "<VibScore>\n  <Clef id=\"c\"/></VibScore>", 2, 3,
                 "needs an href"},
        BadScore{"BadClefId", "<VibScore>\n<Clef id=\"a/b\" href=\"x\"/></VibScore>", 2, 1,
                 "clef id \"a/b\""}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(ScoreXml, ReportsEveryProblemNotJustTheFirst) {
    const std::string document = score_with(
        "<Note length=\"9th\" number=\"1\" string=\"1\"/>\n"
        "  <Note length=\"8th\" number=\"10\" string=\"1\"/>");
    try {
        read_score(document, "bad.xml");
        FAIL() << "no error";
    } catch (const DocumentError& error) {
        ASSERT_EQ(error.diagnostics().size(), 2u);
        EXPECT_EQ(error.diagnostics()[1].where.line, 5);
        EXPECT_NE(std::string(error.what()).find("bad.xml:4:3: unknown length"), std::string::npos);
    }
}

TEST(ScoreXml, RefusesMoreBarsThanTheLimit) {
    std::string document = "<VibScore><Clef id=\"c\" href=\"c\"/>";
    for (std::size_t i = 0; i <= limits::bars; ++i) {
        document += "<Bar clef=\"c\"/>";
    }
    document += "</VibScore>";
    const auto diagnostic = first_diagnostic([&] { read_score(document, "big.xml"); });
    EXPECT_NE(diagnostic.message.find("more than 10000 bars"), std::string::npos);
}

TEST(ScoreXml, RefusesMoreSymbolsThanTheLimit) {
    std::string document = "<VibScore><Clef id=\"c\" href=\"c\"/><Bar clef=\"c\">";
    for (std::size_t i = 0; i <= limits::symbols; ++i) {
        document += "<Blank/>";
    }
    document += "</Bar></VibScore>";
    const auto diagnostic = first_diagnostic([&] { read_score(document, "big.xml"); });
    EXPECT_NE(diagnostic.message.find("more than 100000 symbols"), std::string::npos);
}

TEST(ScoreXml, AcceptsExplicitDefaults) {
    const auto score =
        read_score(score_with("<Note length=\"8th\" number=\"1\" string=\"1\" dynamics=\"none\" "
                              "legato=\"0\" portamento=\"0\"/>"),
                   "x")
            .score;
    EXPECT_EQ(std::get<Note>(score.bars[0].symbols[0]), (Note{Length::eighth, 1, 1}));
}

}  // namespace
}  // namespace vibscore
