// The editor's link to the real vibscored: a playback it started finishes, with the reason in
// words, when the daemon dies and so can send nothing.
#include "client/editor/daemon_link.hpp"

#include <gtest/gtest.h>
#include <poll.h>

#include <algorithm>
#include <chrono>

#include "tests/support/daemon_fixture.hpp"

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

}  // namespace
}  // namespace vibscore
