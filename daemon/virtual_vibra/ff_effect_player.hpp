#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "common/usage.hpp"
#include "daemon/play_request.hpp"
#include "daemon/player.hpp"
#include "daemon/virtual_vibra/uinput_ff_device.hpp"

namespace vibscore::daemon {

// The effects uploaded to the virtual vibra, each kept as the score it plays (an exact one, on
// clefs made for it: score/pattern_score.hpp), and played through the same path as Play: a
// PlaybackRequest for the player, so arbitration by usage and adaptation to the backend apply.
// The vibra plays one effect at a time: playing an effect ends the one it played before.
// Runs work with the player where the player lives: at once in tests, on the playback thread in
// vibscored (PlaybackThread::call), so the vibra, served on the bus thread, never touches the
// player from the wrong thread.
using PlayerAccess = std::function<void(const std::function<void(Player&)>&)>;
// The maximum on-time ([limits]) of the vibra's usage now, asked at each play so that a reload
// applies from the next effect, as it does for Play; nothing: no maximum.
using OnTimeLimit = std::function<std::optional<double>()>;

class FfEffectPlayer final : public FfRequests {
  public:
    // An effect that loops until stopped, like any playback of a non-urgent usage, ends at
    // `max_on_time` ("no one holds the vibrator", a game that never sends stop included).
    FfEffectPlayer(PlayerAccess player, Usage usage, double separation_s,
                   OnTimeLimit max_on_time = {});
    ~FfEffectPlayer() override;
    FfEffectPlayer(const FfEffectPlayer&) = delete;
    FfEffectPlayer& operator=(const FfEffectPlayer&) = delete;

    // Refuses (-EINVAL) what ff_effect_pattern() cannot play. An update of a playing effect
    // reaches its next play.
    int upload(const ff_effect& effect) override;
    void erase(int id) override;
    // Plays `count` times (each with its delay, as ff-memless repeats); 0 stops. A play the
    // player refuses (a more important playback holds the actuator) is dropped and logged.
    void play(int id, int count) override;
    // Scales every play from now on, as the playback's intensity.
    void gain(int value) override;

    std::size_t effects() const { return effects_.size(); }
    double current_gain() const { return gain_; }

  private:
    void stop_playing();

    PlayerAccess with_player_;
    Usage usage_;
    double separation_s_;
    OnTimeLimit max_on_time_;
    double gain_ = 1.0;
    struct Effect {
        ScoreToPlay score;
        bool loops = false;  // played over and over until stopped (ff_effect_loops)
    };
    std::map<int, Effect> effects_;  // by the id the kernel gave
    int playing_effect_ = -1;
    std::uint64_t playback_ = 0;  // the player's id of what the vibra plays; 0: none
};

}  // namespace vibscore::daemon
