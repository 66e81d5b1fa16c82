// [actuator]: the declaration read from its lines, each key's limits at both edges, and every
// error naming the file, line, key and value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "actuator/declaration.hpp"

namespace vibscore::actuator {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::vector<Setting> lines(std::vector<std::pair<std::string, std::string>> pairs) {
    std::vector<Setting> settings;
    int line = 2;
    for (auto& [key, value] : pairs) {
        settings.push_back({key, value, "v.conf:" + std::to_string(line++)});
    }
    return settings;
}

Declaration parse(std::vector<std::pair<std::string, std::string>> pairs) {
    return parse_declaration(lines(std::move(pairs)), "v.conf:1");
}

std::string error_of(std::vector<std::pair<std::string, std::string>> pairs) {
    try {
        parse(std::move(pairs));
    } catch (const DeclarationError& error) {
        return error.what();
    }
    return "<no error>";
}

TEST(ActuatorDeclaration, ReadsTheIssuesErm) {
    const Declaration d = parse({{"kind", "erm"},
                                 {"rated-drive", "0.7"},
                                 {"spin-up-ms", "40"},
                                 {"spin-down-ms", "80"},
                                 {"brake", "reverse"},
                                 {"compensation", "on"}});
    EXPECT_EQ(d.kind, Kind::erm);
    EXPECT_EQ(d.rated_drive, 0.7);
    EXPECT_DOUBLE_EQ(d.spin_up_s, 0.040);
    EXPECT_DOUBLE_EQ(d.spin_down_s, 0.080);
    EXPECT_EQ(d.brake, Brake::reverse);
    EXPECT_TRUE(d.compensation);
}

TEST(ActuatorDeclaration, ReadsAnLraAndDefaultsTheRest) {
    const Declaration d = parse({{"kind", "lra"}, {"resonance-hz", "205.5"}, {"q", "12"}});
    EXPECT_EQ(d.kind, Kind::lra);
    EXPECT_EQ(d.resonance_hz, 205.5);
    EXPECT_EQ(d.q, 12.0);
    EXPECT_EQ(d.rated_drive, 1.0);
    EXPECT_EQ(d.brake, Brake::none);
    EXPECT_TRUE(d.compensation);  // on when the section is there
    EXPECT_FALSE(parse({{"kind", "lra"}, {"compensation", "off"}}).compensation);
    EXPECT_EQ(parse({{"kind", "lra"}, {"brake", "none"}}).brake, Brake::none);
}

TEST(ActuatorDeclaration, AnLrasTolerancesDefaultToThePartToPartSpreadAndZeroIsExact) {
    const Declaration d = parse({{"kind", "lra"}});
    EXPECT_EQ(d.resonance_tolerance, 0.05);
    EXPECT_EQ(d.q_tolerance, 0.40);
    const Declaration exact = parse(
        {{"kind", "lra"}, {"resonance-tolerance-percent", "0"}, {"q-tolerance-percent", "0"}});
    EXPECT_EQ(exact.resonance_tolerance, 0.0);
    EXPECT_EQ(exact.q_tolerance, 0.0);
    const Declaration measured = parse(
        {{"kind", "lra"}, {"resonance-tolerance-percent", "1"}, {"q-tolerance-percent", "15"}});
    EXPECT_DOUBLE_EQ(measured.resonance_tolerance, 0.01);
    EXPECT_DOUBLE_EQ(measured.q_tolerance, 0.15);
}

TEST(ActuatorDeclaration, KindIsRequired) {
    try {
        parse({{"rated-drive", "0.7"}});
        FAIL();
    } catch (const DeclarationError& error) {
        EXPECT_EQ(std::string(error.what()), "v.conf:1: [actuator] needs kind = erm or lra");
        EXPECT_EQ(error.key(), "kind");
    }
}

// Each number: the last value allowed and the first refused, at both ends.
TEST(ActuatorDeclaration, EveryLimitHoldsAtBothEdges) {
    struct Edge {
        const char* kind;
        const char* key;
        const char* allowed;
        const char* refused;
    };
    const Edge edges[] = {
        {"erm", "rated-drive", "1", "1.0000001"},
        {"erm", "rated-drive", "0.0001", "0"},
        {"erm", "spin-up-ms", "1", "0.999"},
        {"erm", "spin-up-ms", "5000", "5000.001"},
        {"erm", "spin-down-ms", "1", "0.999"},
        {"erm", "spin-down-ms", "10000", "10000.1"},
        {"lra", "resonance-hz", "10", "9.99"},
        {"lra", "resonance-hz", "1000", "1000.01"},
        {"lra", "q", "1", "0.99"},
        {"lra", "q", "500", "500.1"},
        {"lra", "resonance-tolerance-percent", "0", "-0.001"},
        {"lra", "resonance-tolerance-percent", "50", "50.001"},
        {"lra", "q-tolerance-percent", "0", "-0.001"},
        {"lra", "q-tolerance-percent", "90", "90.001"},
    };
    for (const auto& edge : edges) {
        EXPECT_NO_THROW(parse({{"kind", edge.kind}, {edge.key, edge.allowed}}))
            << edge.key << " = " << edge.allowed;
        const std::string error = error_of({{"kind", edge.kind}, {edge.key, edge.refused}});
        EXPECT_THAT(error, StartsWith("v.conf:3: [actuator] " + std::string(edge.key) + " = \"" +
                                      edge.refused + "\": expected a number"))
            << error;
    }
    EXPECT_EQ(error_of({{"kind", "erm"}, {"rated-drive", "0"}}),
              "v.conf:3: [actuator] rated-drive = \"0\": expected a number above 0 and at most 1 "
              "(at least 2.2250738585072014e-308)");
    EXPECT_EQ(error_of({{"kind", "lra"}, {"q", "0.5"}}),
              "v.conf:3: [actuator] q = \"0.5\": expected a number from 1 to 500");
}

TEST(ActuatorDeclaration, AboveZeroMeansANormalNumberNotASubnormal) {
    // The largest subnormal, and the smallest of all, are refused as 0 is; the smallest normal
    // number passes that rule (and is refused by the model's, below).
    for (const char* subnormal : {"2.2250738585072009e-308", "5e-324"}) {
        EXPECT_EQ(error_of({{"kind", "erm"}, {"rated-drive", subnormal}}),
                  "v.conf:3: [actuator] rated-drive = \"" + std::string(subnormal) +
                      "\": expected a number above 0 and at most 1 (at least "
                      "2.2250738585072014e-308)");
    }
    EXPECT_THAT(error_of({{"kind", "erm"}, {"rated-drive", "2.2250738585072014e-308"}}),
                HasSubstr("the actuator's model is not finite with it"));
}

TEST(ActuatorDeclaration, ARatedDriveThatMakesTheModelInfiniteIsRefusedAtItsEdge) {
    // A strength is a drive over rated-drive, and the model squares strengths: below about
    // 1 / sqrt(DBL_MAX) the square overflows and the simulation gives NaN (issue 33: 5e-324 wrote
    // NaN in 26,399 of 28,000 rows). The smallest value each kind takes, and the largest it
    // refuses.
    struct Edge {
        const char* kind;
        const char* accepted;
        const char* refused;
    };
    for (const auto& edge : {Edge{"erm", "7.458340731096627e-155", "7.458340731096626e-155"},
                             Edge{"lra", "7.458340731200207e-155", "7.458340731200206e-155"}}) {
        EXPECT_EQ(error_of({{"kind", edge.kind}, {"rated-drive", edge.accepted}}), "<no error>")
            << edge.kind;
        EXPECT_EQ(error_of({{"kind", edge.kind}, {"rated-drive", edge.refused}}),
                  "v.conf:3: [actuator] rated-drive = \"" + std::string(edge.refused) +
                      "\": the actuator's model is not finite with it (the strength under full "
                      "drive at its own frequency is 1.3407807929942597e+154, and its square "
                      "overflows); a rated-drive this small is no actuator: give the drive it is "
                      "rated for")
            << edge.kind;
    }
}

TEST(ActuatorDeclaration, WhatIsNotANumberOrAChoiceIsNamed) {
    EXPECT_EQ(error_of({{"kind", "piezo"}}),
              "v.conf:2: [actuator] kind = \"piezo\": expected erm or lra");
    EXPECT_EQ(error_of({{"kind", "erm"}, {"brake", "short"}}),
              "v.conf:3: [actuator] brake = \"short\": expected none or reverse");
    EXPECT_EQ(error_of({{"kind", "erm"}, {"compensation", "yes"}}),
              "v.conf:3: [actuator] compensation = \"yes\": expected on or off");
    for (const char* bad : {"fast", "40ms", "inf", "nan", "1e999", " "}) {
        EXPECT_THAT(error_of({{"kind", "erm"}, {"spin-up-ms", bad}}),
                    HasSubstr("spin-up-ms = \"" + std::string(bad) + "\""));
    }
    EXPECT_EQ(error_of({{"kind", "erm"}, {"q", ""}}), "v.conf:3: [actuator] q has no value");
}

TEST(ActuatorDeclaration, AKeyOfTheOtherKindIsAnError) {
    EXPECT_EQ(error_of({{"kind", "erm"}, {"resonance-hz", "175"}}),
              "v.conf:3: [actuator] resonance-hz = \"175\" is for kind = lra; this actuator is "
              "kind = erm");
    EXPECT_THAT(error_of({{"q", "15"}, {"kind", "erm"}}), StartsWith("v.conf:2: [actuator] q"));
    EXPECT_THAT(error_of({{"kind", "lra"}, {"spin-down-ms", "80"}}),
                HasSubstr("is for kind = erm; this actuator is kind = lra"));
    EXPECT_EQ(error_of({{"kind", "erm"}, {"q-tolerance-percent", "10"}}),
              "v.conf:3: [actuator] q-tolerance-percent = \"10\" is for kind = lra; this "
              "actuator is kind = erm");
    EXPECT_THAT(error_of({{"kind", "erm"}, {"resonance-tolerance-percent", "1"}}),
                HasSubstr("is for kind = lra"));
}

TEST(ActuatorDeclaration, AnUnknownKeyNamesTheClosestAndEveryKnownOne) {
    const std::string error = error_of({{"kind", "erm"}, {"spinup-ms", "40"}});
    EXPECT_THAT(error, StartsWith("v.conf:3: unknown key \"spinup-ms\" in [actuator] (did you "
                                  "mean spin-up-ms?); known: kind, rated-drive, spin-up-ms"));
    EXPECT_THAT(error, HasSubstr("compensation"));
}

TEST(ActuatorDeclaration, AKeySetTwiceIsAnError) {
    EXPECT_EQ(error_of({{"kind", "erm"}, {"rated-drive", "0.7"}, {"rated-drive", "0.8"}}),
              "v.conf:4: [actuator] rated-drive is set twice (first at v.conf:3)");
}

TEST(ActuatorDeclaration, AFileGivesItsSectionAndSkipsTheOthers) {
    const std::string text =
        "[daemon]\ndriver = sim\nkind = nonsense\n\n"
        "[actuator]   # the board's vibra\n"
        "kind = lra\nq = 20 ; sharp\n"
        "[sim]\nq = 3\n";
    const auto section = find_section(text, "board.conf");
    ASSERT_TRUE(section);
    EXPECT_EQ(section->where, "board.conf:5");
    ASSERT_EQ(section->settings.size(), 2u);
    EXPECT_EQ(section->settings[1].key, "q");
    EXPECT_EQ(section->settings[1].value, "20");
    EXPECT_EQ(section->settings[1].where, "board.conf:7");
    EXPECT_EQ(read_declaration(text, "board.conf")->q, 20.0);
    EXPECT_FALSE(read_declaration("[sim]\nq = 3\n", "x"));
    try {
        read_declaration("[actuator]\nkind lra\n", "bad.conf");
        FAIL();
    } catch (const DeclarationError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "bad.conf:2: expected \"key = value\", found \"kind lra\"");
    }
}

// The file is read by the daemon's reader (common/ini_reader.hpp): a line it refuses is refused
// in any section, and a malformed "[actuator" header is an error, not a section quietly skipped.
TEST(ActuatorDeclaration, AFileIsReadByTheDaemonsStrictRules) {
    const auto error_in = [](const std::string& text) {
        try {
            find_section(text, "f.conf");
        } catch (const DeclarationError& error) {
            return std::string(error.what());
        }
        return std::string("<no error>");
    };
    EXPECT_EQ(error_in("[actuator\nkind = lra\n"),
              "f.conf:1: malformed section header \"[actuator\"");
    EXPECT_THAT(error_in("[actuator]\nkind = lra#x\n"),
                StartsWith("f.conf:2: kind = \"lra#x\" holds '#'"));
    EXPECT_THAT(error_in("[sim]\nmodel = erm;x\n[actuator]\nkind = lra\n"),
                StartsWith("f.conf:2: model = \"erm;x\" holds ';'"));
    // The last allowed: the mark after a blank starts a comment.
    EXPECT_EQ(read_declaration("[actuator]\nkind = lra #x\n", "f.conf")->kind, Kind::lra);
}

TEST(ActuatorDeclaration, ThePropertyReadsBackWhatToSettingsWrites) {
    const Declaration lra = parse({{"kind", "lra"}, {"resonance-hz", "170"}, {"q", "22"}});
    const auto pairs = to_settings(lra);
    EXPECT_EQ(from_settings({pairs.begin(), pairs.end()}, "the property"), lra);
    try {
        from_settings({{"kind", "lra"}, {"q", "0"}}, "the property");
        FAIL();
    } catch (const DeclarationError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "the property: [actuator] q = \"0\": expected a number from 1 to 500");
    }
}

TEST(ActuatorDeclaration, WritesBackWhatItReads) {
    for (const Declaration& d :
         {parse({{"kind", "erm"},
                 {"rated-drive", "0.7"},
                 {"spin-up-ms", "35.5"},
                 {"brake", "reverse"}}),
          parse({{"kind", "lra"}, {"resonance-hz", "170"}, {"q", "22"}, {"compensation", "off"}}),
          parse({{"kind", "lra"},
                 {"resonance-tolerance-percent", "1"},
                 {"q-tolerance-percent", "0"}})}) {
        std::vector<std::pair<std::string, std::string>> pairs;
        for (const auto& [key, value] : to_settings(d)) {
            pairs.emplace_back(key, value);
        }
        EXPECT_EQ(parse(pairs), d);
    }
}

TEST(ActuatorDeclaration, WritesTheTolerancesOnlyWhereTheyAreNotTheDefaults) {
    const auto keys = [](const Declaration& d) {
        std::vector<std::string> written;
        for (const auto& [key, value] : to_settings(d)) {
            written.push_back(key);
        }
        return written;
    };
    EXPECT_THAT(keys(parse({{"kind", "lra"}})), Not(Contains("q-tolerance-percent")));
    EXPECT_THAT(keys(parse({{"kind", "lra"}})), Not(Contains("resonance-tolerance-percent")));
    EXPECT_THAT(
        keys(parse({{"kind", "lra"}, {"q-tolerance-percent", "15"}})),
        AllOf(Contains("q-tolerance-percent"), Not(Contains("resonance-tolerance-percent"))));
}

TEST(ActuatorDeclaration, DescribesItselfInOneLine) {
    EXPECT_EQ(describe(parse({{"kind", "erm"}, {"rated-drive", "0.7"}, {"brake", "reverse"}})),
              "erm: spin-up 40 ms, spin-down 80 ms, rated-drive 0.7, brake reverse, "
              "compensation on");
    EXPECT_EQ(describe(parse({{"kind", "lra"}, {"compensation", "off"}})),
              "lra: resonance 175 Hz, q 15 (envelope 27.3 ms), rated-drive 1, brake none, "
              "compensation off");
}

}  // namespace
}  // namespace vibscore::actuator
