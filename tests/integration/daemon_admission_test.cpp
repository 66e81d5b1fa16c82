// Issue 33, row 1: admission by work. A user's flood of 1 MiB inline scores from several
// connections is refused with LimitExceeded before its documents are parsed, while another
// connection of the same user and root still have their calls answered. The real vibscored on
// a private bus; the flooder runs as uid 65534 (setpriv), its own process.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

using testing::DaemonFixture;
using ::testing::HasSubstr;
using testing::wait_until;

constexpr uid_t kNobody = 65534;
constexpr const char* kLimitExceeded = "org.vibscore.Haptics1.Error.LimitExceeded";

// A user may send 1 MiB of documents a second, in bursts of 2 MiB: each of the flooder's four
// connections 1 MiB at once (half), the four together 1.5 MiB before the reserve.
class DaemonAdmission : public ::testing::Test {
  protected:
    DaemonFixture daemon{
        "[limits]\ndocument-bytes-per-second = 1048576\ndocument-burst-bytes = 2097152\n"};

    std::unique_ptr<testing::Process> flood(int connections) {
        const char* client = std::getenv("VIBSCORE_FLOOD_CLIENT");
        if (client == nullptr) {
            throw std::runtime_error("the test runner must set VIBSCORE_FLOOD_CLIENT");
        }
        return std::make_unique<testing::Process>(
            std::vector<std::string>{"/usr/bin/setpriv", "--reuid=" + std::to_string(kNobody),
                                     "--regid=" + std::to_string(kNobody), "--clear-groups", "--",
                                     "/usr/bin/env",
                                     "DBUS_SYSTEM_BUS_ADDRESS=" + daemon.bus_address(), client,
                                     std::to_string(connections)},
            flood_log_);
    }
    std::string flood_log() const { return testing::read_file(flood_log_); }

  private:
    std::filesystem::path flood_log_ = daemon.store().parent_path() / "flood.log";
};

TEST_F(DaemonAdmission, AFloodingUserIsRefusedBeforeParsingWhileItsOtherAppAndRootAreAnswered) {
    auto flooder = flood(4);
    // The flood is refused for the bytes it sends, by its user's budget...
    ASSERT_TRUE(wait_until(
        [&] {
            return flood_log().find(std::string(kLimitExceeded) +
                                    ": too many document bytes from uid 65534") !=
                   std::string::npos;
        },
        std::chrono::seconds(30)))
        << flood_log() << daemon.daemon_log();
    // (what was admitted is answered once the worker has parsed it)
    EXPECT_TRUE(wait_until([&] { return flood_log().find("admitted") != std::string::npos; },
                           std::chrono::seconds(30)))
        << flood_log() << daemon.daemon_log();
    ASSERT_TRUE(flooder->running()) << flood_log();

    // ...while it goes on, another connection of the same user is answered, a Play too...
    for (int i = 0; i < 5; ++i) {
        const auto listed = daemon.call({"List", "s", "score"}, kNobody);
        EXPECT_EQ(listed.exit_code, 0) << listed.err;
        const auto played = daemon.call({"Play", "sa{sv}", "touch-tick", "0"}, kNobody);
        EXPECT_EQ(played.exit_code, 0) << played.err;
    }
    // ...and so is root, whose calls are never charged.
    auto root = daemon.client();
    for (int i = 0; i < 20; ++i) {
        EXPECT_NO_THROW(root->List("score"));
        EXPECT_NO_THROW(root->Stop(root->Play("touch-tick", {})));
    }
    EXPECT_TRUE(flooder->running()) << "the flood went on meanwhile";
}

TEST_F(DaemonAdmission, AConnectionOverItsShareIsRefusedNamingItsKeyAndOthersAreNot) {
    auto flooder = flood(1);
    ASSERT_TRUE(wait_until(
        [&] {
            return flood_log().find("[limits] connection-share") != std::string::npos ||
                   flood_log().find("has spent its share") != std::string::npos;
        },
        std::chrono::seconds(30)))
        << flood_log();
    // One connection may spend only its share: its user's other connections are not refused.
    const auto listed = daemon.call({"List", "s", "score"}, kNobody);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
}

}  // namespace
}  // namespace vibscore
