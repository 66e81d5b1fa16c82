// vibscored runs in the guest: a private dbus-daemon with the real policy, the daemon with the
// simulated actuator, and one Play through the bus (the fixture of
// tests/integration/daemon_bus_test).
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/support/daemon_fixture.hpp"

namespace vibscore::hil {
namespace {

using testing::DaemonFixture;

TEST(DaemonSmoke, VibscoredPlaysAScoreInTheGuest) {
    DaemonFixture daemon;
    auto client = daemon.client();
    const auto id = client->Play(
        "<VibScore><Title>smoke</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
        "<Bar clef=\"l\"><Note length=\"16th\" number=\"9\" string=\"6\"/></Bar></VibScore>",
        {});
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed") << daemon.daemon_log();
    const auto rows = daemon.trace_rows();
    ASSERT_FALSE(rows.empty()) << daemon.daemon_log();
    double loudest = 0;
    for (const auto& row : rows) {
        loudest = std::max(loudest, row.amplitude);
    }
    EXPECT_GT(loudest, 0.0);
    EXPECT_EQ(rows.back().amplitude, 0.0);
}

}  // namespace
}  // namespace vibscore::hil
