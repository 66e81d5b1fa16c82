// vibscored's named errors in the words a person reads (the CLI and the editor's status line).
#include <gtest/gtest.h>

#include "client/editor/daemon_errors.hpp"

namespace vibscore::client {
namespace {

TEST(DaemonErrorWords, EachNamedErrorOfTheInterfaceHasItsWords) {
    using namespace haptics1::errors;
    const std::pair<const char*, const char*> table[] = {
        {kInvalidDocument, "invalid: m"},
        {kOutOfRange, "out of range: m"},
        {kNotFound, "not found: m"},
        {kPermissionDenied, "not permitted: m"},
        {kLimitExceeded, "over a limit: m"},
        {kBusy, "busy: m"},
        {kDevice, "actuator failed: m"},
        {kNoAccelerometer, "no accelerometer: m"},
        {kUntrusted, "not trusted: m"},
        {kCoolingDown, "cooling down: m"},
    };
    for (const auto& [name, words] : table) {
        EXPECT_EQ(describe_daemon_error(name, "m"), words) << name;
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
