// vibscored's command line and the configuration it asks for, without starting the daemon.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "config.h"
#include "daemon/command_line.hpp"
#include "json/build_tree.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

std::variant<CommandLine, int> parse(std::vector<const char*> arguments) {
    arguments.insert(arguments.begin(), "vibscored");
    return parse_command_line(static_cast<int>(arguments.size()), arguments.data());
}

TEST(CommandLine, NoArgumentsServeWithTheDefaultConfigFile) {
    const auto parsed = std::get<CommandLine>(parse({}));
    EXPECT_EQ(parsed.config, "/etc/vibscore/vibscored.conf");
    EXPECT_FALSE(parsed.config_given);
    EXPECT_FALSE(parsed.list_drivers);
    EXPECT_FALSE(parsed.verbose);
}

TEST(CommandLine, EveryOptionIsTaken) {
    const auto parsed = std::get<CommandLine>(
        parse({"--config", "/tmp/v.conf", "--driver", "evdev", "--store", "/tmp/s", "--shipped",
               "/tmp/c", "--verbose", "--list-drivers"}));
    EXPECT_EQ(parsed.config, "/tmp/v.conf");
    EXPECT_TRUE(parsed.config_given);
    EXPECT_EQ(parsed.driver, "evdev");
    EXPECT_EQ(parsed.store, "/tmp/s");
    EXPECT_EQ(parsed.shipped, "/tmp/c");
    EXPECT_TRUE(parsed.verbose);
    EXPECT_TRUE(parsed.list_drivers);
}

TEST(CommandLine, HelpAndVersionEndWithSuccess) {
    ::testing::internal::CaptureStdout();
    EXPECT_EQ(std::get<int>(parse({"--help"})), 0);
    EXPECT_EQ(std::get<int>(parse({"--version"})), 0);
    const std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_THAT(out, ::testing::HasSubstr("--list-drivers"));
    EXPECT_THAT(out, ::testing::HasSubstr("vibscored " VIBSCORE_VERSION));
}

TEST(CommandLine, AnUnknownOptionOrAnExtraArgumentIsAUsageErrorNamingIt) {
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(std::get<int>(parse({"--bogus"})), 2);
    EXPECT_EQ(std::get<int>(parse({"extra"})), 2);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_THAT(err, ::testing::HasSubstr("vibscored: "));
    EXPECT_THAT(err, ::testing::HasSubstr("--bogus"));
    EXPECT_THAT(err, ::testing::HasSubstr("extra"));
}

TEST(ReadConfig, AMissingDefaultFileMeansTheBuiltInDefaultsAndTheShippedClefs) {
    CommandLine command_line;
    command_line.config = "/nonexistent/vibscored.conf";
    const DaemonConfig config = read_config(command_line);
    EXPECT_EQ(config.driver, "sim");
    // The installed folder; this test, in a build tree, gets its checkout's (build_tree_test).
    EXPECT_EQ(config.shipped, shipped_clefs_folder());
}

TEST(ReadConfig, AMissingFileNamedOnTheCommandLineIsAnError) {
    CommandLine command_line;
    command_line.config = "/nonexistent/vibscored.conf";
    command_line.config_given = true;
    EXPECT_THROW(read_config(command_line), ConfigError);
}

TEST(ReadConfig, TheCommandLineOverridesTheFile) {
    vibscore::testing::TempDir dir;
    CommandLine command_line;
    command_line.config =
        dir.write("v.conf", "[daemon]\ndriver = evdev\nstore = /a\nshipped = /b\n").string();
    EXPECT_EQ(read_config(command_line).driver, "evdev");
    EXPECT_EQ(read_config(command_line).store, "/a");
    command_line.driver = "sim";
    command_line.store = "/x";
    command_line.shipped = "/y";
    const DaemonConfig config = read_config(command_line);
    EXPECT_EQ(config.driver, "sim");
    EXPECT_EQ(config.store, "/x");
    EXPECT_EQ(config.shipped, "/y");
    // Messages about these values must not point at the file's lines, which said otherwise.
    EXPECT_EQ(config.where("daemon", "driver"), "");
    EXPECT_EQ(config.where("daemon", "store"), "");
}

TEST(ReadConfig, AConfigurationFileThatIsADirectoryIsAnErrorNotTheDefaults) {
    vibscore::testing::TempDir dir;
    CommandLine command_line;
    command_line.config = dir.path().string();
    EXPECT_THROW(read_config(command_line), ConfigError) << "the default path, a directory";
    command_line.config_given = true;
    EXPECT_THROW(read_config(command_line), ConfigError);
}

}  // namespace
}  // namespace vibscore::daemon
