#pragma once

#include <cstdint>

#include "feedback/play_request.hpp"

namespace vibscore::feedback {

// What the event table plays through: vibscored's public API (HapticsLink), or a fake in the
// unit tests. What ends later is reported to EventTable::playback_finished.
class Haptics {
  public:
    struct Played {
        std::uint64_t playback = 0;  // 0 (never an id): nothing plays
        bool unknown_score = false;  // vibscored has no score of that name
    };

    virtual ~Haptics() = default;
    // Starts a request. Nothing plays when there is nothing to play, when vibscored refuses
    // (Busy: a more important playback holds the actuator) or cannot be reached; each is
    // logged here.
    virtual Played play(const PlayRequest& request) = 0;
    // Asks vibscored to end a playback; its end is reported later. False when the request
    // failed, so that no end will be reported.
    virtual bool stop(std::uint64_t playback) = 0;
};

}  // namespace vibscore::feedback
