// vibscored's named errors in the words a person reads (the CLI and the editor's status line).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "client/editor/daemon_errors.hpp"
#include "tests/support/run_command.hpp"

namespace vibscore::client {
namespace {

TEST(DaemonErrorWords, EachNamedErrorOfTheInterfaceHasItsWords) {
    using namespace haptics1::errors;
    const std::pair<const char*, const char*> table[] = {
        {kInvalidDocument, "invalid: m"},    {kOutOfRange, "out of range: m"},
        {kNotFound, "not found: m"},         {kPermissionDenied, "not permitted: m"},
        {kLimitExceeded, "over a limit: m"}, {kBusy, "busy: m"},
        {kDevice, "actuator failed: m"},     {kNoAccelerometer, "no accelerometer: m"},
        {kUntrusted, "not trusted: m"},      {kCoolingDown, "cooling down: m"},
    };
    for (const auto& [name, words] : table) {
        EXPECT_EQ(describe_daemon_error(name, "m"), words) << name;
    }
}

// The interface's documentation, the names the daemon sends and the client's words agree: every
// error the XML lists has words, and every one the daemon sends is listed.
TEST(DaemonErrorWords, TheInterfaceDocumentsExactlyTheErrorsThatHaveWords) {
    std::ifstream file(testing::required_env("VIBSCORE_HAPTICS1_XML"));
    ASSERT_TRUE(file) << "cannot read org.vibscore.Haptics1.xml";
    std::stringstream text;
    text << file.rdbuf();
    const std::string xml = text.str();
    std::set<std::string> documented;
    const std::regex name(R"(org\.vibscore\.Haptics1\.Error\.[A-Za-z]+)");
    for (auto it = std::sregex_iterator(xml.begin(), xml.end(), name); it != std::sregex_iterator();
         ++it) {
        documented.insert(it->str());
    }
    using namespace haptics1::errors;
    const std::set<std::string> sent{kInvalidDocument, kOutOfRange, kNotFound,    kPermissionDenied,
                                     kLimitExceeded,   kBusy,       kCoolingDown, kDevice,
                                     kNoAccelerometer, kUntrusted};
    EXPECT_EQ(documented, sent);
    for (const auto& error : documented) {
        EXPECT_NE(describe_daemon_error(error, "m").rfind(error, 0), 0u)
            << error << " has no words of its own";
    }
}

TEST(DaemonErrorWords, ANewerDaemonsErrorKeepsItsNameAndAMissingDaemonIsSaidSo) {
    EXPECT_EQ(describe_daemon_error("org.vibscore.Haptics1.Error.Future", "m"),
              "org.vibscore.Haptics1.Error.Future: m");
    EXPECT_EQ(describe_daemon_error(haptics1::errors::kServiceUnknown, "m"),
              "vibscored is not running on the system bus (m)");
    EXPECT_EQ(describe_daemon_error("org.example.Other", "m"), "m (org.example.Other)");
}

}  // namespace
}  // namespace vibscore::client
