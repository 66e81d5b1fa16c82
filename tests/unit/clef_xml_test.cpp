#include <gtest/gtest.h>

#include "score/clef_xml.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::first_diagnostic;

TEST(ClefXml, ReadsASineClefAsInThesisSection32) {
    const Clef clef = read_clef(R"(<VibClef type="sine" version="1.0">
  <Tempo>0.1500</Tempo>
  <Numbers><Number>0.0027</Number><Number>0.0039</Number></Numbers>
  <Strings>
    <String>50</String>
    <String> 300 </String>
  </Strings>
</VibClef>)",
                                "sine.xml");
    EXPECT_EQ(clef.type, ClefType::sine);
    EXPECT_EQ(clef.tempo, 0.15);
    EXPECT_EQ(clef.numbers, (std::vector<double>{0.0027, 0.0039}));
    ASSERT_EQ(clef.strings.size(), 2u);
    EXPECT_EQ(clef.strings[1].frequency, 300.0);
}

TEST(ClefXml, AcceptsNumbersWithoutTheirContainer) {
    const Clef clef = read_clef(
        "<VibClef type=\"sine\"><Tempo>1</Tempo><Number>0.5</Number><Number>1</Number>"
        "<Strings><String>100</String></Strings></VibClef>",
        "x");
    EXPECT_EQ(clef.numbers, (std::vector<double>{0.5, 1.0}));
}

TEST(ClefXml, ReadsCurveAndLineClefPoints) {
    for (const char* type : {"curve", "line"}) {
        const Clef clef = read_clef(std::string("<VibClef type=\"") + type + R"(" version="1.0">
  <Tempo>0.5</Tempo>
  <Numbers><Number>1</Number></Numbers>
  <Strings>
    <String>
      <Point time="0.0000" level="0.3000"/>
      <Point time="0.5" level="1"/>
      <Point time="0.5" level="0"/>
      <Point time="1.0000" level="0.0000"/>
    </String>
  </Strings>
</VibClef>)",
                                    "shape.xml");
        EXPECT_EQ(to_string(clef.type), type);
        ASSERT_EQ(clef.strings.size(), 1u);
        EXPECT_EQ(clef.strings[0].points,
                  (std::vector<ClefPoint>{{0, 0.3}, {0.5, 1}, {0.5, 0}, {1, 0}}));
    }
}

TEST(ClefXml, RoundTripKeepsTheModelExactly) {
    Clef sine;
    sine.tempo = 0.1;
    sine.numbers = {0.1, 1.0 / 3.0, 0.7351};
    sine.strings = {{50.5, {}}, {1e-3, {}}, {19999.999999, {}}};
    EXPECT_EQ(read_clef(write_clef(sine), "x"), sine);

    Clef curve;
    curve.type = ClefType::curve;
    curve.version = "2.1";
    curve.tempo = 0.15;
    curve.numbers = {0.0027};
    curve.strings = {{0, {{0, 0.3}, {0.1 + 0.2, 2.0 / 3.0}, {1, 0}}}};
    const auto written = write_clef(curve);
    EXPECT_EQ(read_clef(written, "x"), curve);
    EXPECT_EQ(write_clef(read_clef(written, "x")), written);
}

struct BadClef {
    const char* name;
    std::string body;  // inside <VibClef type="sine"> on line 2
    int line;
    const char* message_part;
};

class BadClefTest : public ::testing::TestWithParam<BadClef> {};

TEST_P(BadClefTest, NamesLineAndValue) {
    const auto& bad = GetParam();
    const auto diagnostic = first_diagnostic([&] { read_clef(bad.body, "clef.xml"); });
    EXPECT_EQ(diagnostic.where.file, "clef.xml");
    EXPECT_EQ(diagnostic.where.line, bad.line) << diagnostic.message;
    EXPECT_NE(diagnostic.message.find(bad.message_part), std::string::npos) << diagnostic.message;
}

std::string sine_with(const std::string& tempo, const std::string& number,
                      const std::string& frequency) {
    return "<VibClef type=\"sine\">\n<Tempo>" + tempo + "</Tempo>\n<Numbers><Number>" + number +
           "</Number></Numbers>\n<Strings><String>" + frequency + "</String></Strings>\n</VibClef>";
}

std::string line_with(const std::string& points) {
    return "<VibClef type=\"line\">\n<Tempo>1</Tempo>\n<Numbers><Number>1</Number></Numbers>\n"
           "<Strings><String>\n" +
           points + "\n</String></Strings>\n</VibClef>";
}

INSTANTIATE_TEST_SUITE_P(
    ClefXml, BadClefTest,
    ::testing::Values(
        BadClef{"UnknownType", "<VibClef type=\"square\"/>", 1, "unknown clef type \"square\""},
        BadClef{"MissingType", "\n<VibClef/>", 2, "has no type"},
        BadClef{"NanTempo", sine_with("NaN", "1", "100"), 2, "tempo \"NaN\" is not a finite"},
        BadClef{"InfiniteTempo", sine_with("inf", "1", "100"), 2, "is not a finite"},
        BadClef{"NegativeTempo", sine_with("-0.5", "1", "100"), 2,
                "tempo \"-0.5\" is out of range"},
        BadClef{"ZeroTempo", sine_with("0", "1", "100"), 2, "out of range"},
        BadClef{"TextTempo", sine_with("fast", "1", "100"), 2, "tempo \"fast\""},
        BadClef{"NegativeAmplitude", sine_with("1", "-1", "100"), 3,
                "amplitude of number 1 \"-1\" is out of range"},
        BadClef{"HugeAmplitude", sine_with("1", "1e300", "100"), 3, "out of range"},
        BadClef{"NegativeFrequency", sine_with("1", "1", "-50"), 4,
                "frequency of string 1 \"-50\" is out of range"},
        BadClef{"ZeroFrequency", sine_with("1", "1", "0"), 4, "must be above 0 Hz"},
        BadClef{"NanFrequency", sine_with("1", "1", "nan"), 4, "is not a finite"},
        BadClef{"PointsOutOfOrder",
                line_with("<Point time=\"0.5\" level=\"0\"/>\n<Point time=\"0.25\" level=\"1\"/>"),
                6, "point time 0.25 comes before the previous point's 0.5"},
        BadClef{"TimeAboveOne", line_with("<Point time=\"1.5\" level=\"0\"/>"), 5,
                "point time \"1.5\" is out of range (0 to 1)"},
        BadClef{"LevelBelowZero", line_with("<Point time=\"0\" level=\"-0.1\"/>"), 5,
                "point level \"-0.1\" is out of range"},
        BadClef{"PointWithoutLevel", line_with("<Point time=\"0\"/>"), 5, "has no level"},
        BadClef{"StringWithoutPoints", line_with(""), 4, "has no <Point>"},
        BadClef{"PointsInSineString",
                "<VibClef type=\"sine\"><Tempo>1</Tempo><Number>1</Number><Strings>\n<String>"
                "<Point time=\"0\" level=\"1\"/></String></Strings></VibClef>",
                2, "in a String of a sine clef"},
        BadClef{"NoTempo",
                "<VibClef type=\"sine\"><Number>1</Number><Strings><String>1</String></Strings>"
                "</VibClef>",
                1, "has no <Tempo>"},
        BadClef{"NoNumbers",
                "<VibClef type=\"sine\"><Tempo>1</Tempo><Strings><String>1</String></Strings>"
                "</VibClef>",
                1, "defines no <Number>"},
        BadClef{"NoStrings", "<VibClef type=\"sine\"><Tempo>1</Tempo><Number>1</Number></VibClef>",
                1, "defines no <String>"},
        BadClef{"UnknownElement", "<VibClef type=\"sine\">\n<Tempo>1</Tempo>\n<Colour/></VibClef>",
                3, "unknown element <Colour>"},
        BadClef{"WrongRoot", "<VibScore/>", 1, "expected <VibClef>"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(ClefXml, RefusesMoreThanSixStringsAndNineNumbers) {
    std::string strings;
    std::string numbers;
    for (int i = 0; i < 7; ++i) {
        strings += "<String>100</String>";
    }
    for (int i = 0; i < 10; ++i) {
        numbers += "<Number>1</Number>";
    }
    const auto many_strings = first_diagnostic([&] {
        read_clef("<VibClef type=\"sine\"><Tempo>1</Tempo><Number>1</Number><Strings>" + strings +
                      "</Strings></VibClef>",
                  "x");
    });
    EXPECT_NE(many_strings.message.find("more than 6 <String>"), std::string::npos);
    const auto many_numbers = first_diagnostic([&] {
        read_clef("<VibClef type=\"sine\"><Tempo>1</Tempo><Numbers>" + numbers +
                      "</Numbers><Strings><String>1</String></Strings></VibClef>",
                  "x");
    });
    EXPECT_NE(many_numbers.message.find("more than 9 <Number>"), std::string::npos);
}

TEST(ClefXml, RefusesTooManyPoints) {
    std::string points;
    for (int i = 0; i <= 4096; ++i) {
        points += "<Point time=\"0.5\" level=\"0.5\"/>";
    }
    const auto diagnostic = first_diagnostic([&] { read_clef(line_with(points), "x"); });
    EXPECT_NE(diagnostic.message.find("more than 4096 points"), std::string::npos);
}

}  // namespace
}  // namespace vibscore
