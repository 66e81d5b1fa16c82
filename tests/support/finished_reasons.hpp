#pragma once

#include <string>
#include <vector>

#include "daemon/player.hpp"

namespace vibscore::testing {

// A player listener that keeps only why each playback ended, in order.
class FinishedReasons : public daemon::PlayerListener {
  public:
    void playback_started(std::uint64_t, const std::string&) override {}
    void playback_position(std::uint64_t, std::size_t, std::size_t) override {}
    void playback_finished(std::uint64_t, const std::string& reason) override {
        reasons.push_back(reason);
    }
    std::vector<std::string> reasons;
};

}  // namespace vibscore::testing
