// `vibscored --list-drivers` against the configuration it is given: the real program, as a
// package's check or an administrator runs it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::required_env;
using testing::run_command;
using testing::TempDir;

testing::CommandResult list_drivers(const std::filesystem::path& config) {
    return run_command({required_env("VIBSCORED"), "--config", config.string(), "--list-drivers"});
}

TEST(ListDrivers, AGoodConfigurationListsTheDriversAndExitsZero) {
    TempDir dir;
    const auto config = dir.write("good.conf", "[daemon]\ndriver = sim\n");
    const auto result = list_drivers(config);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("sim\t"));
    EXPECT_THAT(result.err, Not(HasSubstr("<3>")));
}

TEST(ListDrivers, ABadConfigurationIsAnErrorNamingItAndExitsOne) {
    TempDir dir;
    const auto config = dir.write("bad.conf", "[daemon]\nseparation-ms = 0\n");
    const auto result = list_drivers(config);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_THAT(result.err,
                HasSubstr("<3>" + config.string() + ":2: separation-ms = \"0\" is not a number"));
    // The default directory's drivers still follow, to help fix the file.
    EXPECT_THAT(result.out, HasSubstr("sim\t"));
}

TEST(ListDrivers, AValueWithANulOrOfAHundredThousandBytesIsQuotedShortAndWhole) {
    TempDir dir;
    const char text[] =
        "[daemon]\nrt-priority = 4\0"
        "2\n";
    const auto nul = dir.write("nul.conf", std::string(text, sizeof text - 1));
    auto result = list_drivers(nul);
    EXPECT_EQ(result.exit_code, 1);
    // Nothing after the NUL is lost: the message goes on past it.
    EXPECT_THAT(result.err, HasSubstr(":2: rt-priority = \"4\\x002\" is not a whole number from 0 "
                                      "to 99\n"));

    const auto huge =
        dir.write("huge.conf", "[daemon]\nrt-priority = " + std::string(100'000, '7') + "\n");
    result = list_drivers(huge);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_THAT(result.err, HasSubstr(":2: rt-priority = \"" + std::string(80, '7') +
                                      "\"... (100000 bytes) is not a whole number from 0 to 99\n"));
    EXPECT_LT(result.err.size(), 1000u) << "the value is echoed whole";
}

}  // namespace
}  // namespace vibscore
