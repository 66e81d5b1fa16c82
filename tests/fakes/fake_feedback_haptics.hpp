#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "feedback/haptics.hpp"

namespace vibscore::testing {

// vibscored as vibscore-feedback's event table sees it, without a bus: each play gets the next
// playback id (from 101) unless the test makes vibscored refuse; stops are recorded and ends
// are reported by the test (EventTable::playback_finished), as vibscored reports them.
class FakeFeedbackHaptics : public feedback::Haptics {
  public:
    Played play(const feedback::PlayRequest& request) override {
        requests.push_back(request);
        if (refuse) {
            return {0, false};
        }
        if (!request.entry.score.empty() && unknown_scores.contains(request.entry.score)) {
            return {0, true};
        }
        playing.insert(next_playback);
        return {next_playback++, false};
    }
    bool stop(std::uint64_t playback) override {
        stops.push_back(playback);
        if (!stop_works) {
            return false;
        }
        playing.erase(playback);
        return true;
    }

    // What the test sets.
    bool refuse = false;     // Busy, or vibscored not there
    bool stop_works = true;  // false: Stop fails, so no end will be reported
    std::set<std::string> unknown_scores;

    // What the table asked.
    std::vector<feedback::PlayRequest> requests;
    std::vector<std::uint64_t> stops;
    std::set<std::uint64_t> playing;
    std::uint64_t next_playback = 101;
};

}  // namespace vibscore::testing
