#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "tests/hil/guest_stalls.hpp"

#include "tests/support/daemon_fixture.hpp"

namespace vibscore::hil {

// A score played to its end on the daemon, with the guest's stalls watched throughout
// (GuestStallMeter): what a daemon-level timing test judges the kernel's record by.
struct WatchedPlayback {
    // The playback finished, and for the reason "completed" (a failure was added otherwise,
    // with the daemon's log).
    bool completed = false;
    // When the Play call was made.
    std::chrono::steady_clock::time_point asked;
    // kOnsetTolerance_s and the longest the guest stopped while the score played
    // (onset_tolerance_s): late by no more, the daemon was on time.
    double onset_tolerance_s = 0.0;
    // Every time the guest stopped while the score played (GuestStallMeter::stalls).
    std::vector<GuestStallMeter::Stall> stalls;

    // How long the guest was stopped between `from` and `to` while the score played: what a
    // stretch of the daemon's work (the Play call to its first edge) may be late by on top
    // of its own bound.
    double stalled_s(std::chrono::steady_clock::time_point from,
                     std::chrono::steady_clock::time_point to) const {
        return hil::stalled_s(stalls, from, to);
    }
};

WatchedPlayback play_to_the_end(testing::DaemonFixture& daemon, const std::string& score);

}  // namespace vibscore::hil
