#include "daemon/virtual_vibra/ff_effect_player.hpp"

#include <algorithm>
#include <cerrno>
#include <memory>

#include "common/log.hpp"
#include "daemon/request_error.hpp"
#include "daemon/virtual_vibra/ff_effect_pattern.hpp"
#include "score/document_error.hpp"

#include <utility>

namespace vibscore::daemon {

FfEffectPlayer::FfEffectPlayer(PlayerAccess player, Usage usage, double separation_s,
                               OnTimeLimit max_on_time)
    : with_player_(std::move(player)),
      usage_(usage),
      separation_s_(separation_s),
      max_on_time_(std::move(max_on_time)) {}

FfEffectPlayer::~FfEffectPlayer() {
    stop_playing();
}

int FfEffectPlayer::upload(const ff_effect& effect) {
    const std::string label =
        "virtual-vibra " + std::to_string(effect.id) + ": " + describe_ff_effect(effect);
    try {
        const auto pattern = ff_effect_pattern(effect);
        effects_[effect.id] = {
            ScoreToPlay{exact_pattern_score(pattern, label, "<" + label + ">"), label},
            ff_effect_loops(effect)};
        log::debug(label + " uploaded");
        return 0;
    } catch (const std::invalid_argument& error) {
        log::debug("virtual-vibra: refused effect " + std::to_string(effect.id) + ": " +
                   error.what());
    } catch (const DocumentError& error) {
        log::warning("virtual-vibra: refused " + label + ": " + error.what());
    }
    return -EINVAL;
}

void FfEffectPlayer::erase(int id) {
    if (id == playing_effect_) {
        stop_playing();
    }
    effects_.erase(id);
}

void FfEffectPlayer::stop_playing() {
    if (playback_ != 0) {
        // As root: the vibra's playbacks belong to nobody on the bus.
        with_player_([this](Player& player) { player.stop(playback_, 0, true); });
    }
    playback_ = 0;
    playing_effect_ = -1;
}

void FfEffectPlayer::play(int id, int count) {
    if (count <= 0) {
        if (id == playing_effect_) {
            stop_playing();
        }
        return;
    }
    const auto effect = effects_.find(id);
    if (effect == effects_.end()) {
        return;
    }
    stop_playing();
    const ScoreToPlay& score = effect->second.score;
    if (score.bundle.score.bars.empty()) {
        return;  // nothing in it to play, and nothing to repeat
    }
    PlayOptions options;
    options.usage = usage_;
    options.repeat = effect->second.loops ? -1 : count - 1;
    options.intensity = gain_;
    try {
        PlaybackRequest request = make_playback_request(score, options, separation_s_);
        request.owner = 0;
        request.sender.clear();  // not a bus client: it ends with its effect
        if (max_on_time_) {
            request.max_on_time_s = max_on_time_();
        }
        // The work owns its request: a playback thread that does not answer in time runs it
        // later or never (PlaybackThread::call).
        const auto started = std::make_shared<std::uint64_t>(0);
        with_player_([request, started](Player& player) { *started = player.play(request); });
        playback_ = *started;
        playing_effect_ = id;
    } catch (const PlayerBusy& busy) {
        log::debug("virtual-vibra: effect " + std::to_string(id) + " not played: " + busy.what());
    } catch (const RequestError& error) {
        log::warning("virtual-vibra: effect " + std::to_string(id) +
                     " not played: " + error.what());
    }
}

void FfEffectPlayer::gain(int value) {
    gain_ = std::clamp(value, 0, 0xffff) / 65535.0;
}

}  // namespace vibscore::daemon
