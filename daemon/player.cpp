#include "daemon/player.hpp"

#include <algorithm>
#include <cmath>

#include "common/log.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/strength_scale.hpp"

namespace vibscore::daemon {

namespace {

// How far the player reads ahead for the next drive to prepare, or for the next switch-off to
// arm a kernel timer with: enough for 20 s of 5 ms steps, and a bound on what one playback holds.
constexpr std::size_t kReadAhead = 4096;

// Stands in while nobody listens, so reporting needs no null checks.
class NobodyListens final : public PlayerListener {
  public:
    void playback_started(std::uint64_t, const std::string&) override {}
    void playback_position(std::uint64_t, std::size_t, std::size_t) override {}
    void playback_finished(std::uint64_t, const std::string&) override {}
};

NobodyListens nobody;

bool is_drive(const render::Cue& cue) {
    return cue.kind == render::Cue::Kind::drive;
}

bool is_off(const drivers::Drive& drive) {
    return drive.amplitude == 0.0 && drive.ramp_to == 0.0;
}

}  // namespace

Player::Player(EventLoop& loop, drivers::Actuator& actuator, PlayerListener* listener,
               std::uint64_t first_id)
    : timer_(loop, [this] { run_due(); }),
      actuator_(&actuator),
      listener_(&nobody),
      first_id_(first_id),
      next_id_(first_id) {
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

std::uint64_t Player::due_us(const Playback& playback, const PassCue& cue) const {
    // Each pass is placed from the start, not from the previous pass, so repeats do not drift.
    const double seconds = static_cast<double>(cue.pass) * playback.request.duration_s + cue.cue.at;
    return playback.start_us + static_cast<std::uint64_t>(std::llround(seconds * 1e6));
}

void Player::check_admission(Usage usage, int repeat) const {
    if (!current_) {
        return;
    }
    const auto& playing = current_->request;
    const int current_importance = importance(playing.usage);
    const int new_importance = importance(usage);
    if (new_importance < current_importance) {
        throw PlayerBusy("a more important playback is in progress (" +
                         std::string(to_string(playing.usage)) + ", id " +
                         std::to_string(current_->id) + ")");
    }
    // Repeats left: the asked ones less the passes already begun after the first.
    const bool repeating =
        playing.repeat < 0 || static_cast<std::uint64_t>(playing.repeat) > current_->pass;
    if (new_importance == current_importance && repeating && repeat == 0) {
        throw PlayerBusy("a repeating " + std::string(to_string(playing.usage)) +
                         " playback is in progress (id " + std::to_string(current_->id) +
                         "); it yields only to a more important or another repeating one");
    }
}

std::uint64_t Player::play(PlaybackRequest request) {
    check_admission(request.usage, request.repeat);
    if (current_) {
        finish("preempted");
    }
    const std::uint64_t id = next_id_++;
    const std::string label = request.label;
    const drivers::Capabilities capabilities = actuator_->capabilities();
    render::CueAdaptation adaptation;
    adaptation.frequency = capabilities.frequency_control;
    adaptation.amplitude = capabilities.amplitude_control;
    adaptation.envelopes = capabilities.envelopes;
    const StrengthScale scale =
        strength_scale(capabilities, request.intensity, master_intensity_, request.probe);
    adaptation.scale = scale.software;
    adaptation.pulse_period_s = capabilities.pulse_period_s;
    if (!request.probe && declared_) {
        adaptation.actuator = declared_;
        adaptation.reverse = capabilities.reverse;
    }
    PlaybackCues cues(request.cues, request.duration_s, request.repeat, adaptation);
    on_since_us_.reset();
    held_off_ = false;
    last_report_us_.reset();
    held_position_.reset();
    const bool final_drives = declared_.has_value() || request.probe;
    current_.emplace(Playback{id, std::move(request), std::move(cues), monotonic_now_us(), 0,
                              capabilities, final_drives});
    if (scale.device_gain) {
        try {
            actuator_->set_gain(*scale.device_gain);
        } catch (const drivers::DeviceError& error) {
            fail(error);  // like a failing first drive: the playback ends, the call succeeds
            return id;
        }
    }
    // The first drive goes out before anything else: it is what the user feels.
    bool drove = false;
    while (const PassCue* next = current_->cues.ahead(0)) {
        if (next->pass != 0 || next->cue.at > 0.0 || !is_drive(next->cue)) {
            break;
        }
        const render::Cue cue = next->cue;
        current_->cues.pop();
        if (!drove) {
            // Counted from here, not from the call: what came before (a device's gain, the
            // first cues worked out) must not shorten the first note's off-timer.
            current_->start_us = monotonic_now_us();
        }
        if (!execute(cue)) {
            return id;
        }
        drove = true;
    }
    if (drove) {
        // The score's clock starts when its first drive has reached the actuator: a backend that
        // first had to find its device again (replugged) can take longer than a short note, which
        // would otherwise be cut off as overdue.
        current_->start_us = monotonic_now_us();
    }
    listener_->playback_started(id, label);
    if (!on_since_us_) {
        prepare_next_drive();  // a score that starts vibrating has prepared its second drive
    }
    run_due();
    return id;
}

void Player::set_actuator(std::optional<actuator::Declaration> declaration) {
    declared_ = std::move(declaration);
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
    if (current_->final_drives) {
        // Planned for the declared actuator: never beyond full scale, and backwards only on a
        // backend that can.
        const double lowest = capabilities.reverse ? -1.0 : 0.0;
        drivers::Drive drive{std::clamp(cue.amplitude, lowest, 1.0), cue.frequency_hz};
        if (cue.ramp_s > 0.0) {
            drive.ramp_to = std::clamp(cue.ramp_to, lowest, 1.0);
            drive.ramp_s = cue.ramp_s;
        }
        return drive;
    }
    // The master as it is now: a SetIntensity during the playback reaches its next drive.
    const double scale = strength_scale(capabilities, current_->request.intensity,
                                        master_intensity_, current_->request.probe)
                             .software;
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
    for (std::size_t i = 0; i < kReadAhead; ++i) {
        const PassCue* next = current_->cues.ahead(i);
        if (next == nullptr) {
            return;
        }
        if (is_drive(next->cue) && !is_off(drive_for(next->cue))) {
            try {
                actuator_->prepare(drive_for(next->cue));
            } catch (const drivers::DeviceError& error) {
                fail(error);
            }
            return;
        }
    }
}

double Player::seconds_until_off() {
    const double limit_s = current_->capabilities.max_on_time_s;
    const std::uint64_t now = monotonic_now_us();
    double until_s = 0.0;
    for (std::size_t i = 0; i < kReadAhead; ++i) {
        const PassCue* next = current_->cues.ahead(i);
        if (next == nullptr) {
            return until_s;  // the playback ends, and the actuator with it, after the last cue
        }
        const std::uint64_t due = due_us(*current_, *next);
        until_s = due > now ? static_cast<double>(due - now) / 1e6 : 0.0;
        if (limit_s > 0.0 && until_s >= limit_s) {
            return limit_s;
        }
        if (is_drive(next->cue) && is_off(drive_for(next->cue))) {
            return until_s;
        }
    }
    // Not in sight: as long as the actuator may be on at all.
    return limit_s > 0.0 ? limit_s : until_s;
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

std::uint64_t Player::next_report_us(std::uint64_t now_us) const {
    std::uint64_t at = positions_.available_at(current_->request.sender, now_us);
    if (last_report_us_) {
        at = std::max(at, *last_report_us_ + kPositionReportInterval_us);
    }
    return at;
}

void Player::report_position(std::size_t bar, std::size_t symbol) {
    held_position_.emplace(bar, symbol);
    report_held_position(false);
}

void Player::report_held_position(bool force) {
    if (!held_position_) {
        return;
    }
    const std::uint64_t now = monotonic_now_us();
    if (!force && last_report_us_ && now < *last_report_us_ + kPositionReportInterval_us) {
        return;
    }
    if (!positions_.take(current_->request.sender, now)) {
        if (force) {
            held_position_.reset();  // PlaybackFinished follows; it is not held back for this
        }
        return;
    }
    last_report_us_ = now;
    const auto [bar, symbol] = *held_position_;
    held_position_.reset();
    listener_->playback_position(current_->id, bar, symbol);
}

bool Player::execute(const render::Cue& cue) {
    if (cue.kind == render::Cue::Kind::position) {
        report_position(cue.bar, cue.symbol);
        return true;
    }
    const drivers::Drive drive = drive_for(cue);
    try {
        if (is_off(drive)) {
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
        if (current_->capabilities.off_timer) {
            actuator_->set_off_timer(seconds_until_off());
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
        report_held_position(false);
        const PassCue* next = playback.cues.ahead(0);
        if (next == nullptr) {
            finish(playback.cues.end_reason());
            return;
        }
        playback.pass = next->pass;
        const std::uint64_t due = due_us(playback, *next);
        const std::uint64_t now = monotonic_now_us();
        const auto max_on_time = playback.request.max_on_time_s;
        const auto limit_deadline = max_on_time_deadline_us(playback.start_us, max_on_time);
        const NextStep step = next_step(now, due, limit_deadline);
        if (step.kind == NextStep::Kind::end_over_limit) {
            log::info("playback " + std::to_string(playback.id) + " (uid " +
                          std::to_string(playback.request.owner) + ", " +
                          std::string(to_string(playback.request.usage)) +
                          ") reached its maximum on-time",
                      {{"PLAYBACK_ID", std::to_string(playback.id)},
                       {"CALLER_UID", std::to_string(playback.request.owner)},
                       {"USAGE", std::string(to_string(playback.request.usage))},
                       {"REASON", "limit-exceeded"}});
            cool_downs_.cut_off(playback.request.owner, now);
            finish(over_on_time_reason(*max_on_time));
            return;
        }
        const auto on_time_deadline = on_time_deadline_us();
        if (on_time_deadline && now >= *on_time_deadline) {
            log::warning("actuator " + std::string(actuator_->driver_name()) + " was on for its " +
                         "maximum on-time; held off until the score pauses (playback " +
                         std::to_string(playback.id) + ")");
            actuator_->off();
            on_since_us_.reset();
            held_off_ = true;
        }
        if (step.kind == NextStep::Kind::wait) {
            std::uint64_t wake = step.wake_us;
            if (on_since_us_ && on_time_deadline) {
                wake = std::min(wake, *on_time_deadline);
            }
            if (held_position_) {
                wake = std::min(wake, next_report_us(now));
            }
            timer_.arm(wake);
            return;
        }
        const render::Cue cue = next->cue;
        playback.cues.pop();
        if (!execute(cue)) {
            return;
        }
    }
}

void Player::finish(std::string reason) {  // a copy: it may live in the playback that ends
    if (!current_) {
        return;
    }
    actuator_->off();
    timer_.disarm();
    report_held_position(true);  // where it got to, before it is said to have ended
    const std::uint64_t id = current_->id;
    current_.reset();
    listener_->playback_finished(id, reason);
}

Player::StopResult Player::stop(std::uint64_t id, uid_t caller, bool privileged) {
    if (id != 0 && (id < first_id_ || id >= next_id_)) {
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
    finish(kStopped);
    return StopResult::stopped;
}

void Player::sender_vanished(const std::string& sender) {
    if (!current_ || current_->request.sender != sender || current_->request.repeat == 0) {
        return;
    }
    // A playback that soon ends by itself is the caller's fire-and-forget request (busctl, a
    // script, a ringtone rung three times): it plays to its end.
    const auto& playback = *current_;
    if (playback.request.repeat > 0) {
        const double total_s =
            (static_cast<double>(playback.request.repeat) + 1.0) * playback.request.duration_s;
        const double end_us = static_cast<double>(playback.start_us) + total_s * 1e6;
        if (end_us <= static_cast<double>(monotonic_now_us()) + kPlaysOnWithoutItsCaller_s * 1e6) {
            return;
        }
    }
    finish("client-vanished");
}

void Player::check_cool_down(uid_t owner, Usage usage, int repeat, double cool_down_s) const {
    cool_downs_.check(owner, usage, repeat, cool_down_s, monotonic_now_us());
}

std::vector<std::uint64_t> Player::stop_every_playback() {
    if (!current_) {
        return {};
    }
    const std::uint64_t id = current_->id;
    // An administrator ended it: its user may not re-take the actuator at once.
    cool_downs_.cut_off(current_->request.owner, monotonic_now_us());
    finish(kStopped);
    return {id};
}

void Player::stop_all(const std::string& reason) {
    finish(reason);
    actuator_->off();
}

void Player::replace_actuator(drivers::Actuator& actuator) {
    stop_all(kStopped);
    actuator_ = &actuator;
    actuator_->off();
}

}  // namespace vibscore::daemon
