// vibscored.conf without a daemon: every [daemon] key, driver sections, and each error naming
// the file, line and value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "daemon/config.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string config_error(const std::string& text) {
    try {
        parse_config(text, "test.conf");
    } catch (const ConfigError& error) {
        return error.what();
    }
    return "<no error>";
}

TEST(Config, AnEmptyFileKeepsTheDefaults) {
    DaemonConfig defaults;
    defaults.shipped = "/usr/share/vibscore/clefs";
    const DaemonConfig config = parse_config("# nothing\n\n   ; here either\n", "x", defaults);
    EXPECT_EQ(config.driver, "sim");
    EXPECT_EQ(config.store, "/var/lib/vibscore");
    EXPECT_EQ(config.shipped, "/usr/share/vibscore/clefs");
    EXPECT_EQ(config.separation_ms, 30.0);
    EXPECT_EQ(config.requests_per_second, 50.0);
    EXPECT_EQ(config.request_burst, 100.0);
    EXPECT_TRUE(config.driver_settings.empty());
}

TEST(Config, EveryDaemonKeyIsRead) {
    const DaemonConfig config = parse_config(
        "[daemon]\n"
        "driver = gpio-erm\n"
        "drivers-dir = /opt/drivers\n"
        "store = /tmp/store\n"
        "shipped = /tmp/shipped\n"
        "separation-ms = 12.5\n"
        "requests-per-second = 7\n"
        "request-burst = 9\n"
        "rt-priority = 0\n",
        "x");
    EXPECT_EQ(config.driver, "gpio-erm");
    EXPECT_EQ(config.drivers_dir, "/opt/drivers");
    EXPECT_EQ(config.store, "/tmp/store");
    EXPECT_EQ(config.shipped, "/tmp/shipped");
    EXPECT_EQ(config.separation_ms, 12.5);
    EXPECT_EQ(config.requests_per_second, 7.0);
    EXPECT_EQ(config.request_burst, 9.0);
    EXPECT_EQ(config.rt_priority, 0);
}

TEST(Config, SpacesAndCommentsAfterKeysAndValuesAreDropped) {
    const DaemonConfig config =
        parse_config("  [ daemon ]  # the service\n\tdriver\t=  evdev   ; the vibra\n", "x");
    EXPECT_EQ(config.driver, "evdev");
}

TEST(Config, OtherSectionsAreTheSettingsOfTheDriverTheyName) {
    const DaemonConfig config = parse_config(
        "[sim]\nmodel = erm\ntrace = /tmp/t.csv\n[evdev]\ndevice = /dev/input/event3\n", "x");
    EXPECT_EQ(config.settings_of("sim"),
              (std::map<std::string, std::string>{{"model", "erm"}, {"trace", "/tmp/t.csv"}}));
    EXPECT_EQ(config.settings_of("evdev").at("device"), "/dev/input/event3");
    EXPECT_TRUE(config.settings_of("gpio-lra").empty());
}

TEST(Config, AKeySetTwiceInASectionIsAnErrorNamingBothLinesAndValues) {
    EXPECT_EQ(config_error("[daemon]\ndriver = evdev\n\ndriver = sim\n"),
              "test.conf:4: driver = \"sim\" sets [daemon] driver again (test.conf:2 set it to "
              "\"evdev\"); keep one of them");
    // In a backend's section, across two headers of one section, and in [clefs].
    EXPECT_THAT(config_error("[sim]\nmodel = erm\n[daemon]\n[sim]\nmodel = lra\n"),
                StartsWith("test.conf:5: model = \"lra\" sets [sim] model again (test.conf:2"));
    EXPECT_THAT(config_error("[clefs]\n* = a\nlra-phone = b\n* = c\n"),
                StartsWith("test.conf:4: * = \"c\" sets [clefs] * again (test.conf:2"));
    // One key in two sections is two settings.
    const auto config = parse_config("[sim]\ntrace = /a\n[trace]\npath = /a\n", "x");
    EXPECT_EQ(config.settings_of("sim").at("trace"), "/a");
}

TEST(Config, ACommentStartsAtTheStartOfALineOrAfterABlank) {
    const auto config = parse_config(
        "# a line\n  ; another\n[daemon]\t# the service\nstore = /data/store  # kept here\n"
        "shipped = /data/shipped\t; there\n",
        "x");
    EXPECT_EQ(config.store, "/data/store");
    EXPECT_EQ(config.shipped, "/data/shipped");
}

TEST(Config, AHashOrSemicolonInsideAValueIsAnErrorNotACutShortValue) {
    EXPECT_EQ(config_error("[daemon]\nstore = /var/lib/vib#score\n"),
              "test.conf:2: store = \"/var/lib/vib#score\" holds '#', which starts a comment "
              "only at the start of a line or after a space; a value cannot contain it");
    EXPECT_THAT(config_error("[sim]\ntrace = /tmp/a;b.csv\n"),
                StartsWith("test.conf:2: trace = \"/tmp/a;b.csv\" holds ';'"));
    EXPECT_THAT(config_error("[sim]# erm\n"), StartsWith("test.conf:1: \"[sim]# erm\" holds '#'"));
}

TEST(Config, AMalformedLineIsAnErrorNamingFileAndLine) {
    EXPECT_EQ(config_error("[daemon]\n\ndriver sim\n"),
              "test.conf:3: expected \"key = value\", found \"driver sim\"");
    EXPECT_EQ(config_error("[daemon\n"), "test.conf:1: malformed section header \"[daemon\"");
    EXPECT_EQ(config_error("[]\n"), "test.conf:1: malformed section header \"[]\"");
    EXPECT_EQ(config_error("driver = sim\n"), "test.conf:1: \"driver\" is outside any [section]");
}

TEST(Config, AnUnknownDaemonKeyIsAnErrorListingTheKnownOnes) {
    const auto message = config_error("[daemon]\ndriverr = sim\n");
    EXPECT_THAT(message, StartsWith("test.conf:2: unknown key \"driverr\" in [daemon] (did you "
                                    "mean driver?)"));
    EXPECT_THAT(message, HasSubstr("requests-per-second"));
    EXPECT_THAT(config_error("[daemon]\ncolour = red\n"),
                StartsWith("test.conf:2: unknown key \"colour\" in [daemon] (expected driver"));
}

TEST(Config, TheRequestBurstLetsAtLeastOneRequestThrough) {
    EXPECT_EQ(parse_config("[daemon]\nrequest-burst = 1\n", "x").request_burst, 1.0);
    EXPECT_EQ(config_error("[daemon]\nrequest-burst = 0.99999\n"),
              "test.conf:2: request-burst = \"0.99999\" is below 1: the burst must let at least "
              "one request through");
    EXPECT_THAT(config_error("[daemon]\nrequest-burst = 0.5\n"),
                StartsWith("test.conf:2: request-burst = \"0.5\" is below 1"));
    EXPECT_EQ(parse_config("[daemon]\nrequest-burst = 1000000\n", "x").request_burst, 1e6);
    EXPECT_THAT(config_error("[daemon]\nrequest-burst = 1000000.5\n"),
                StartsWith("test.conf:2: request-burst = \"1000000.5\" is not a number"));
}

TEST(Config, ANumberThatIsNotPositiveOrTooLargeOrNotANumberIsAnError) {
    for (const auto* value : {"0", "-5", "abc", "12ms", "nan", "inf", "1001"}) {
        EXPECT_THAT(config_error(std::string("[daemon]\nseparation-ms = ") + value + "\n"),
                    StartsWith(std::string("test.conf:2: separation-ms = \"") + value +
                               "\" is not a number above 0 and at most"))
            << value;
    }
    EXPECT_THAT(config_error("[daemon]\nrequests-per-second = 0\n"),
                StartsWith("test.conf:2: requests-per-second = \"0\""));
    EXPECT_THAT(config_error("[daemon]\nrequest-burst = x\n"),
                StartsWith("test.conf:2: request-burst = \"x\""));
}

TEST(Config, AboveZeroMeansANormalNumberNotASubnormal) {
    // The smallest normal double is the smallest value taken; the largest subnormal is refused
    // as 0 is, and so is the smallest subnormal.
    for (const char* key : {"separation-ms", "requests-per-second"}) {
        const std::string line = std::string("[daemon]\n") + key + " = ";
        EXPECT_NO_THROW(parse_config(line + "2.2250738585072014e-308\n", "x")) << key;
        for (const char* subnormal : {"2.2250738585072009e-308", "5e-324"}) {
            EXPECT_THAT(config_error(line + subnormal + "\n"),
                        StartsWith("test.conf:2: " + std::string(key) + " = \"" + subnormal +
                                   "\" is not a number above 0 and at most "))
                << key;
        }
    }
    EXPECT_THAT(config_error("[daemon]\nseparation-ms = 0\n"),
                ::testing::EndsWith(" (the smallest above 0 is 2.2250738585072014e-308)"));
    // The one rule in [actuator] too.
    EXPECT_THAT(config_error("[actuator]\nkind = erm\nrated-drive = 5e-324\n"),
                StartsWith("test.conf:3: [actuator] rated-drive = \"5e-324\": expected a number "
                           "above 0"));
}

TEST(Config, AValueIsQuotedAtMostEightyBytesLongWithItsControlCharactersEscaped) {
    // A NUL no longer ends the message, and what follows it is shown.
    EXPECT_EQ(config_error(std::string("[daemon]\nseparation-ms = 1\0x\n", 29)),
              "test.conf:2: separation-ms = \"1\\x00x\" is not a number above 0 and at most 1000 "
              "(the smallest above 0 is 2.2250738585072014e-308)");
    // 100,000 characters: 80 of them, then the size.
    const std::string long_value(100'000, '9');
    EXPECT_EQ(config_error("[daemon]\nrt-priority = " + long_value + "\n"),
              "test.conf:2: rt-priority = \"" + std::string(80, '9') +
                  "\"... (100000 bytes) is not a whole number from 0 to 99");
    // Keys, section headers, lines and [clefs] and [actuator] values alike.
    for (const std::string& text :
         {"[daemon]\n" + long_value + " = 1\n", "[" + long_value + "\n", long_value + "\n",
          "[clefs]\nshaker = " + long_value + "X\n", "[clefs]\nfit = " + long_value + "\n",
          "[actuator]\nkind = " + long_value + "\n", "[actuator]\n" + long_value + "\n",
          "[daemon]\nstore = a\nstore = " + long_value + "\n"}) {
        const std::string error = config_error(text);
        EXPECT_LT(error.size(), 400u) << error.substr(0, 400);
        EXPECT_THAT(error, HasSubstr("... (100"));
    }
    const std::string control = config_error("[clefs]\nfit = \x1b[31mred\x7f\n");
    EXPECT_EQ(control, "test.conf:2: [clefs] fit = \"\\x1b[31mred\\x7f\" is neither auto nor off");
}

TEST(Config, ADriversSettingIsQuotedTheSameWay) {
    const std::string long_value(100'000, 'x');
    drivers::DriverSettings bad_value("sim", {{"lines", std::string("1\0"
                                                                    "7",
                                                                    3)}});
    try {
        bad_value.integer("lines", 0, 1, 99);
        ADD_FAILURE() << "no error";
    } catch (const drivers::SettingError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "sim setting lines = \"1\\x007\": expected a whole number from 1 to 99");
    }
    drivers::DriverSettings unknown("sim", {{long_value, long_value}});
    try {
        unknown.reject_unknown();
        ADD_FAILURE() << "no error";
    } catch (const drivers::SettingError& error) {
        const std::string message = error.what();
        EXPECT_THAT(message, StartsWith("unknown sim setting " + std::string(80, 'x') +
                                        "... (100000 bytes) = \"" + std::string(80, 'x') +
                                        "\"... (100000 bytes)"));
        EXPECT_LT(message.size(), 600u);
    }
}

TEST(Config, ThePlaybackThreadsPriorityIsAWholeNumberUpTo99) {
    EXPECT_EQ(parse_config("", "x").rt_priority, 40);
    EXPECT_EQ(parse_config("[daemon]\nrt-priority = 99\n", "x").rt_priority, 99);
    for (const auto* value : {"-1", "100", "5.5", "high"}) {
        EXPECT_EQ(config_error(std::string("[daemon]\nrt-priority = ") + value + "\n"),
                  std::string("test.conf:2: rt-priority = \"") + value +
                      "\" is not a whole number from 0 to 99")
            << value;
    }
}

TEST(Config, AKeyWithoutAValueIsAnError) {
    EXPECT_EQ(config_error("[daemon]\nstore =\n"), "test.conf:2: store has no value");
}

TEST(Config, AFileThatCannotBeOpenedIsAnErrorNamingItAndTheReason) {
    try {
        load_config("/nonexistent/vibscored.conf");
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "/nonexistent/vibscored.conf: cannot open: No such file or directory");
    }
}

TEST(Config, EachSettingRemembersItsFileAndLine) {
    const auto config =
        parse_config("[daemon]\ndriver = sim\n\n[sim]\nmodel = erm\n[led-vibrator]\n", "t.conf");
    EXPECT_EQ(config.where("sim", "model"), "t.conf:5: ");
    EXPECT_EQ(config.where("sim", "max-on-time-ms"), "t.conf:4: ");
    EXPECT_EQ(config.where("led-vibrator", "led"), "t.conf:6: ");
    EXPECT_EQ(DaemonConfig{}.where("sim", "model"), "");
}

TEST(Config, AnUnknownSectionIsAWarningWithItsLineAndTheClosestName) {
    const auto config = parse_config(
        "[daemon]\n[led-vibrater]\nled = x\n[sim]\n[zzzzzz]\n[virtual-vibra]\n", "t.conf");
    EXPECT_THAT(unknown_sections(config, {"sim", "led-vibrator", "evdev"}),
                ::testing::ElementsAre(
                    "t.conf:2: unknown section [led-vibrater]: no driver of that name, so its keys "
                    "apply nowhere (did you mean [led-vibrator]?)",
                    "t.conf:5: unknown section [zzzzzz]: no driver of that name, so its keys apply "
                    "nowhere"));
    EXPECT_THAT(unknown_sections(config, {"sim", "led-vibrater", "zzzzzz"}), ::testing::IsEmpty());
}

TEST(Config, TheActuatorIsDeclaredInItsOwnSection) {
    EXPECT_FALSE(parse_config("[daemon]\ndriver = sim\n", "t.conf").actuator);
    const auto config = parse_config(
        "[daemon]\ndriver = gpio-erm\n"
        "[actuator]\nkind = erm\nrated-drive = 0.7\nspin-up-ms = 40\nspin-down-ms = 80\n"
        "brake = reverse\ncompensation = on\n",
        "t.conf");
    ASSERT_TRUE(config.actuator);
    EXPECT_EQ(config.actuator->kind, actuator::Kind::erm);
    EXPECT_EQ(config.actuator->rated_drive, 0.7);
    EXPECT_EQ(config.actuator->brake, actuator::Brake::reverse);
    // A section of the service, not a driver's: no warning.
    EXPECT_THAT(unknown_sections(config, {"sim", "gpio-erm"}), ::testing::IsEmpty());
}

TEST(Config, AnActuatorErrorNamesTheFileLineKeyAndValue) {
    EXPECT_EQ(config_error("[actuator]\nkind = lra\nq = 0\n"),
              "test.conf:3: [actuator] q = \"0\": expected a number from 1 to 500");
    EXPECT_EQ(config_error("[daemon]\n\n[actuator]\nrated-drive = 0.7\n"),
              "test.conf:3: [actuator] needs kind = erm or lra");
    EXPECT_THAT(config_error("[actuator]\nkind = erm\nq = 15\n"),
                StartsWith("test.conf:3: [actuator] q = \"15\" is for kind = lra"));
    EXPECT_THAT(config_error("[actuator]\nkind = erm\nbrakes = reverse\n"),
                StartsWith("test.conf:3: unknown key \"brakes\" in [actuator] (did you mean "
                           "brake?)"));
    EXPECT_EQ(config_error("[actuator]\nkind = erm\nbrake =\n"),
              "test.conf:3: [actuator] brake has no value");
}

TEST(Config, ADirectoryIsNotAConfigurationFile) {
    vibscore::testing::TempDir dir;
    try {
        load_config(dir.path());
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& error) {
        EXPECT_EQ(std::string(error.what()),
                  dir.path().string() + ": is a directory, not a configuration file");
    }
}

TEST(Config, EveryDaemonKeyAndClefMapRemembersItsLine) {
    const auto config =
        parse_config("[daemon]\ndriver = evdev\n[clefs]\nlra-phone = b\n* = c\n", "t.conf");
    EXPECT_EQ(config.where("daemon", "driver"), "t.conf:2: ");
    EXPECT_EQ(config.where("clefs", "lra-phone"), "t.conf:4: ");
    EXPECT_EQ(config.where("clefs", "*"), "t.conf:5: ");
}

TEST(Config, AFileIsReadWithItsPathInErrors) {
    vibscore::testing::TempDir dir;
    const auto path = dir.write("vibscored.conf", "[daemon]\nrequest-burst = 3\n[daemon]\nx = 1\n");
    EXPECT_EQ(load_config(dir.write("good.conf", "[daemon]\nrequest-burst = 3\n")).request_burst,
              3.0);
    try {
        load_config(path);
        ADD_FAILURE() << "no error";
    } catch (const ConfigError& error) {
        EXPECT_THAT(error.what(), StartsWith(path.string() + ":4: unknown key \"x\""));
    }
}

}  // namespace
}  // namespace vibscore::daemon
