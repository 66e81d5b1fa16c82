#include "tests/hil/watched_playback.hpp"

#include <gtest/gtest.h>

#include "tests/hil/guest_stalls.hpp"
#include "tests/hil/score_expectations.hpp"

namespace vibscore::hil {

WatchedPlayback play_to_the_end(testing::DaemonFixture& daemon, const std::string& score) {
    auto client = daemon.client();
    WatchedPlayback played;
    GuestStallMeter stalls;
    played.asked = std::chrono::steady_clock::now();
    const auto id = client->Play(score, {});
    std::string reason;
    if (!client->wait_finished(id, &reason)) {
        ADD_FAILURE() << "the playback did not finish\n" << daemon.daemon_log();
        return played;
    }
    played.onset_tolerance_s = onset_tolerance_s(stalls);
    played.stalls = stalls.stalls();
    played.completed = reason == "completed";
    if (!played.completed) {
        ADD_FAILURE() << "the playback finished with " << reason << "\n" << daemon.daemon_log();
    }
    return played;
}

}  // namespace vibscore::hil
