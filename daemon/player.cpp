#include "daemon/player.hpp"

#include <algorithm>
#include <cmath>

#include "daemon/log.hpp"

namespace vibscore::daemon {

Player::Player(EventLoop& loop, drivers::Actuator& actuator, PlayerListener& listener)
    : timer_(loop, [this] { run_due(); }), actuator_(&actuator), listener_(listener) {
    actuator_->off();  // whatever state the device was left in
}

Player::~Player() {
    actuator_->off();
}

std::optional<std::uint64_t> Player::current_id() const {
    return current_ ? std::optional(current_->id) : std::nullopt;
}

std::uint64_t Player::due_us(const Playback& playback, const render::Cue& cue) const {
    // Each pass is placed from the start, not from the previous pass, so repeats do not drift.
    const double seconds =
        static_cast<double>(playback.pass) * playback.request.duration_s + cue.at;
    return playback.start_us + static_cast<std::uint64_t>(std::llround(seconds * 1e6));
}

std::uint64_t Player::play(PlaybackRequest request) {
    if (current_) {
        const auto& playing = current_->request;
        const int current_importance = importance(playing.usage);
        const int new_importance = importance(request.usage);
        if (new_importance < current_importance) {
            throw PlayerBusy("a more important playback is in progress (" +
                             std::string(to_string(playing.usage)) + ", id " +
                             std::to_string(current_->id) + ")");
        }
        if (new_importance == current_importance && playing.repeat != 0 && request.repeat == 0) {
            throw PlayerBusy("a repeating " + std::string(to_string(playing.usage)) +
                             " playback is in progress (id " + std::to_string(current_->id) +
                             "); it yields only to a more important or another repeating one");
        }
        finish("preempted");
    }
    const std::uint64_t id = next_id_++;
    const std::string label = request.label;
    current_ = Playback{id, std::move(request), monotonic_now_us(), 0, 0};
    // The first drive goes out before anything else: it is what the user feels.
    auto& cues = current_->request.cues;
    while (current_->next_cue < cues.size() && cues[current_->next_cue].at <= 0.0 &&
           cues[current_->next_cue].kind == render::Cue::Kind::drive) {
        if (!execute(cues[current_->next_cue++])) {
            return id;
        }
    }
    listener_.playback_started(id, label);
    run_due();
    return id;
}

bool Player::execute(const render::Cue& cue) {
    if (cue.kind == render::Cue::Kind::position) {
        listener_.playback_position(current_->id, cue.bar, cue.symbol);
        return true;
    }
    const double scale = current_->request.intensity * master_intensity_;
    const drivers::Drive drive{std::clamp(cue.amplitude * scale, 0.0, 1.0), cue.frequency_hz};
    try {
        if (drive.amplitude == 0.0) {
            actuator_->off();
        } else {
            actuator_->apply(drive);
        }
        return true;
    } catch (const drivers::DeviceError& error) {
        log::error(std::string("actuator failed: ") + error.what());
        finish(std::string("device-error: ") + error.what());
        return false;
    }
}

void Player::run_due() {
    while (current_) {
        auto& playback = *current_;
        const auto& cues = playback.request.cues;
        if (playback.next_cue == cues.size()) {
            if (playback.request.repeat == 0) {
                finish("completed");
                return;
            }
            if (playback.request.repeat > 0) {
                --playback.request.repeat;
            }
            ++playback.pass;
            playback.next_cue = 0;
            if (cues.empty()) {
                continue;
            }
        }
        const auto& cue = cues[playback.next_cue];
        const std::uint64_t due = due_us(playback, cue);
        if (due > monotonic_now_us()) {
            timer_.arm(due);
            return;
        }
        ++playback.next_cue;
        if (!execute(cue)) {
            return;
        }
    }
}

void Player::finish(const std::string& reason) {
    if (!current_) {
        return;
    }
    actuator_->off();
    timer_.disarm();
    const std::uint64_t id = current_->id;
    current_.reset();
    listener_.playback_finished(id, reason);
}

Player::StopResult Player::stop(std::uint64_t id, uid_t caller, bool privileged) {
    if (id >= next_id_) {
        return StopResult::not_found;
    }
    if (!current_ || (id != 0 && current_->id != id)) {
        return StopResult::not_playing;
    }
    if (current_->request.owner != caller) {
        if (id == 0) {
            return StopResult::not_playing;  // 0 means "mine"; nothing of the caller's plays
        }
        if (!privileged) {
            return StopResult::not_permitted;
        }
    }
    finish("stopped");
    return StopResult::stopped;
}

void Player::sender_vanished(const std::string& sender) {
    if (current_ && current_->request.sender == sender) {
        finish("client-vanished");
    }
}

void Player::stop_all(const std::string& reason) {
    finish(reason);
    actuator_->off();
}

void Player::replace_actuator(drivers::Actuator& actuator) {
    stop_all("stopped");
    actuator_ = &actuator;
    actuator_->off();
}

}  // namespace vibscore::daemon
