// The editor's link to the real vibscored: a playback it started finishes, with the reason in
// words, when the daemon dies and so can send nothing.
#include "client/editor/daemon_link.hpp"

#include <gtest/gtest.h>
#include <poll.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "client/editor/daemon_watch.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore {
namespace {

const char* const kLongScore =
    "<VibScore><Title>long</Title><Clef id=\"l\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"l\"><Note length=\"whole\" number=\"9\" string=\"6\"/></Bar>"
    "<Bar clef=\"l\"><Note length=\"whole\" number=\"9\" string=\"6\"/></Bar></VibScore>";

// Serves the link's bus until `id` finishes (or `limit` passes); the finish's reason, or "".
std::string reason_finished(editor::DaemonLink& link, std::uint64_t id,
                            std::chrono::milliseconds limit = std::chrono::seconds(10)) {
    const auto give_up = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < give_up) {
        pollfd fd{link.fd(), link.events(), 0};
        ::poll(&fd, 1, std::min(link.timeout_ms() < 0 ? 100 : link.timeout_ms(), 100));
        for (const auto& event : link.process()) {
            if (event.id == id && event.kind == editor::PlaybackEvent::Kind::finished) {
                return event.reason;
            }
        }
    }
    return "";
}

TEST(EditorDaemonLink, APlaybackEndsSayingSoWhenTheDaemonIsKilled) {
    testing::DaemonFixture daemon;
    editor::DaemonLink link;
    const auto id = link.play(kLongScore, 0);
    daemon.kill_daemon();
    EXPECT_EQ(reason_finished(link, id), "vibscored left the bus");
}

TEST(EditorDaemonLink, APlaybackThatEndsNormallyIsNotReportedTwice) {
    testing::DaemonFixture daemon;
    editor::DaemonLink link;
    const auto id = link.play(kLongScore, 0);
    link.stop(id);
    EXPECT_EQ(reason_finished(link, id), "stopped");
    daemon.kill_daemon();
    EXPECT_EQ(reason_finished(link, id, std::chrono::milliseconds(500)), "");
}

// `vibscore play --wait` watches vibscored's name; the name's changes come on the event loop's
// thread and may come as the watch is destroyed. None may reach it once it is gone: a change
// written into its state after that state was destroyed was a leak the sanitizer build caught
// at exit (once in CI). Thousands of watches come and go here while the name changes owner as
// fast as the bus allows; then one watch must still see its daemon leave.
TEST(ClientDaemonWatch, GoesSafelyWhileTheNameChangesOnAnotherThreadAndSeesTheDaemonLeave) {
    testing::DaemonFixture daemon;
    ASSERT_EQ(daemon.stop_daemon(), 0);
    const auto watching = sdbus::createSystemBusConnection();
    watching->enterEventLoopAsync();
    const auto owner = sdbus::createSystemBusConnection();
    {
        std::atomic<bool> done{false};
        std::thread changing([&] {
            const auto flapping = sdbus::createSystemBusConnection();
            while (!done) {
                dbus::request_name(*flapping, haptics1::kBusName);
                dbus::release_name(*flapping, haptics1::kBusName);
            }
        });
        for (int watch = 0; watch < 2000; ++watch) {
            const auto passing = std::make_unique<client::DaemonWatch>(*watching);
            passing->follow();
            (void)passing->gone();
        }
        done = true;
        changing.join();
    }
    dbus::request_name(*owner, haptics1::kBusName);
    client::DaemonWatch watch(*watching);
    watch.follow();
    EXPECT_EQ(watch.gone(), std::nullopt);
    dbus::release_name(*owner, haptics1::kBusName);
    EXPECT_TRUE(testing::wait_until([&] { return watch.gone().has_value(); }));
    EXPECT_EQ(watch.gone(), "vibscored left the bus");
    watching->leaveEventLoop();
}

}  // namespace
}  // namespace vibscore
