#include "daemon/player.hpp"

#include <algorithm>
#include <cmath>

#include "daemon/log.hpp"
#include "daemon/render/cue_adaptation.hpp"

namespace vibscore::daemon {

namespace {

// Stands in while nobody listens, so reporting needs no null checks.
class NobodyListens final : public PlayerListener {
  public:
    void playback_started(std::uint64_t, const std::string&) override {}
    void playback_position(std::uint64_t, std::size_t, std::size_t) override {}
    void playback_finished(std::uint64_t, const std::string&) override {}
};

NobodyListens nobody;

}  // namespace

Player::Player(EventLoop& loop, drivers::Actuator& actuator, PlayerListener* listener)
    : timer_(loop, [this] { run_due(); }), actuator_(&actuator), listener_(&nobody) {
    set_listener(listener);
    actuator_->off();  // whatever state the device was left in
}

void Player::set_listener(PlayerListener* listener) {
    listener_ = listener != nullptr ? listener : &nobody;
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
    const drivers::Capabilities capabilities = actuator_->capabilities();
    render::CueAdaptation adaptation;
    adaptation.frequency = capabilities.frequency_control;
    adaptation.amplitude = capabilities.amplitude_control;
    adaptation.envelopes = capabilities.envelopes;
    adaptation.scale = request.intensity * master_intensity_;
    adaptation.pulse_period_s = capabilities.pulse_period_s;
    request.cues = render::adapt_cues(request.cues, request.duration_s, adaptation);
    on_since_us_.reset();
    held_off_ = false;
    current_ = Playback{id, std::move(request), monotonic_now_us(), 0, 0, capabilities};
    if (capabilities.gain_control) {
        try {
            actuator_->set_gain(master_intensity_);
        } catch (const drivers::DeviceError& error) {
            fail(error);  // like a failing first drive: the playback ends, the call succeeds
            return id;
        }
    }
    // The first drive goes out before anything else: it is what the user feels.
    auto& cues = current_->request.cues;
    while (current_->next_cue < cues.size() && cues[current_->next_cue].at <= 0.0 &&
           cues[current_->next_cue].kind == render::Cue::Kind::drive) {
        if (!execute(cues[current_->next_cue++])) {
            return id;
        }
    }
    listener_->playback_started(id, label);
    if (!on_since_us_) {
        prepare_next_drive();  // a score that starts vibrating has prepared its second drive
    }
    run_due();
    return id;
}

void Player::set_master_intensity(double intensity) {
    master_intensity_ = intensity;
    if (actuator_->capabilities().gain_control) {
        try {
            actuator_->set_gain(intensity);
        } catch (const drivers::DeviceError& error) {
            // The next play sets the gain again; a failing device shows there.
            log::warning(std::string("actuator gain: ") + error.what());
        }
    }
}

drivers::Drive Player::drive_for(const render::Cue& cue) const {
    const auto& capabilities = current_->capabilities;
    if (!capabilities.amplitude_control) {
        return {cue.amplitude > 0.0 ? 1.0 : 0.0, cue.frequency_hz};  // pulses carry the strength
    }
    double scale = current_->request.intensity;
    if (!capabilities.gain_control) {
        scale *= master_intensity_;
    }
    drivers::Drive drive{std::clamp(cue.amplitude * scale, 0.0, 1.0), cue.frequency_hz};
    if (cue.ramp_s > 0.0) {
        drive.ramp_to = std::clamp(cue.ramp_to * scale, 0.0, 1.0);
        drive.ramp_s = cue.ramp_s;
    }
    return drive;
}

// Effect-memory backends get the next drive ahead of its onset, so starting it costs one write.
void Player::prepare_next_drive() {
    if (!current_ || !current_->capabilities.effect_memory) {
        return;
    }
    const auto& cues = current_->request.cues;
    const auto is_drive = [](const render::Cue& cue) {
        return cue.kind == render::Cue::Kind::drive && cue.amplitude > 0.0;
    };
    auto next = std::find_if(cues.begin() + static_cast<std::ptrdiff_t>(current_->next_cue),
                             cues.end(), is_drive);
    if (next == cues.end() && current_->request.repeat != 0) {
        next = std::find_if(cues.begin(), cues.end(), is_drive);
    }
    if (next == cues.end()) {
        return;
    }
    try {
        actuator_->prepare(drive_for(*next));
    } catch (const drivers::DeviceError& error) {
        fail(error);
    }
}

void Player::fail(const drivers::DeviceError& error) {
    log::error(std::string("actuator failed: ") + error.what());
    finish(std::string("device-error: ") + error.what());
}

std::optional<std::uint64_t> Player::on_time_deadline_us() const {
    const double limit_s = current_->capabilities.max_on_time_s;
    if (limit_s <= 0.0 || !on_since_us_) {
        return std::nullopt;
    }
    return *on_since_us_ + static_cast<std::uint64_t>(std::llround(limit_s * 1e6));
}

bool Player::execute(const render::Cue& cue) {
    if (cue.kind == render::Cue::Kind::position) {
        listener_->playback_position(current_->id, cue.bar, cue.symbol);
        return true;
    }
    const drivers::Drive drive = drive_for(cue);
    try {
        if (drive.amplitude == 0.0 && drive.ramp_to == 0.0) {
            actuator_->off();
            on_since_us_.reset();
            held_off_ = false;
            return true;
        }
        if (held_off_) {
            return true;  // cooling down until the score gives the actuator a break
        }
        if (!on_since_us_) {
            on_since_us_ = monotonic_now_us();
        }
        actuator_->apply(drive);
        prepare_next_drive();
        return current_.has_value();
    } catch (const drivers::DeviceError& error) {
        fail(error);
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
        const std::uint64_t now = monotonic_now_us();
        const auto on_time_deadline = on_time_deadline_us();
        if (on_time_deadline && now >= *on_time_deadline) {
            log::warning("actuator " + std::string(actuator_->driver_name()) + " was on for its " +
                         "maximum on-time; held off until the score pauses (playback " +
                         std::to_string(playback.id) + ")");
            actuator_->off();
            on_since_us_.reset();
            held_off_ = true;
        }
        if (due > now) {
            std::uint64_t wake = due;
            if (on_since_us_ && on_time_deadline) {
                wake = std::min(wake, *on_time_deadline);
            }
            timer_.arm(wake);
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
    listener_->playback_finished(id, reason);
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
    // A playback that ends by itself is the caller's fire-and-forget request (busctl, a script):
    // it plays to its end. Only one that would repeat forever needs its caller to stop it.
    if (current_ && current_->request.sender == sender && current_->request.repeat < 0) {
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
