#include "feedback/feedback_service.hpp"
#include "dbus/sdbus_compat.hpp"

#include <algorithm>
#include <cmath>

#include "common/monotonic_clock.hpp"
#include "daemon/log.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"

namespace vibscore::feedback {

namespace {

constexpr const char* kObjectPath = "/org/sigxcpu/Feedback";
constexpr const char* kInvalidArgs = "org.freedesktop.DBus.Error.InvalidArgs";

// feedbackd's limits on a Haptic.Vibrate pattern (fbd-haptic-manager.c).
constexpr std::size_t kMaxPatternSteps = 10;
constexpr std::uint32_t kMaxStepMs = 10'000;

sdbus::Error invalid_args(const std::string& message) {
    return dbus::bus_error(kInvalidArgs, message);
}

// The level TriggerFeedback's hints ask for: "profile" may only lower it.
Profile hinted_level(const std::map<std::string, sdbus::Variant>& hints, Profile level) {
    const auto hint = hints.find("profile");
    if (hint == hints.end()) {
        return level;
    }
    const std::string held = dbus::variant_signature(hint->second);
    if (held != "s") {
        throw invalid_args("hint \"profile\" must be a string (s), not " + held);
    }
    const auto name = hint->second.get<std::string>();
    const auto hinted = parse_profile(name);
    if (!hinted) {
        throw invalid_args("hint \"profile\": unknown profile \"" + name + "\" (expected " +
                           std::string(kProfileNames) + ")");
    }
    return std::min(level, *hinted);
}

}  // namespace

FeedbackService::FeedbackService(sdbus::IConnection& session_bus, sdbus::IConnection& system_bus,
                                 daemon::EventLoop& loop, Theme theme, ServiceSettings settings)
    : AdaptorInterfaces(session_bus, dbus::object_path(kObjectPath)),
      haptics_(system_bus, {[this](std::uint64_t playback, const std::string& reason) {
                                playback_finished(playback, reason);
                            },
                            [this] { haptics_gone(); }}),
      theme_(std::move(theme)),
      settings_(std::move(settings)),
      profile_(settings_.profile),
      expiry_(loop, [this] { expire(); }) {
    vanish_watch_ = dbus::watch_connections_leaving(session_bus, [this](const std::string& name) {
        end_where([&](const Event& event) { return event.sender == name; },
                  end_reason::explicit_end);
    });
    registerAdaptor();
}

FeedbackService::~FeedbackService() {
    unregisterAdaptor();
}

std::uint64_t FeedbackService::play(const ThemeEntry& entry, const std::string& title, int repeat) {
    try {
        std::string score = entry.score;
        double intensity = entry.intensity;
        if (score.empty()) {
            if (pattern_seconds(entry.pattern) <= 0.0) {
                return 0;  // nothing to play, and nothing to repeat
            }
            auto on_clef =
                pattern_on_clef(entry.pattern, title, kPatternClefHref, haptics_.pattern_clef());
            score = std::move(on_clef.document);
            intensity *= on_clef.intensity;
        }
        std::map<std::string, sdbus::Variant> options{
            {"usage", sdbus::Variant(entry.usage)},
            {"repeat", sdbus::Variant(static_cast<std::int32_t>(repeat))},
            {"intensity", sdbus::Variant(intensity)},
        };
        if (!entry.clef.empty()) {
            options.emplace("clef", sdbus::Variant(entry.clef));
        }
        return haptics_.Play(score, options);
    } catch (const sdbus::Error& error) {
        // Busy: a more important playback holds the actuator, as feedbackd's busy vibra.
        if (error.getName() == haptics1::errors::kBusy) {
            log::debug("vibscored is busy: " + error.getMessage());
        } else {
            log::warning("vibscored did not play \"" + title + "\": " + error.getName() + ": " +
                         error.getMessage());
        }
    } catch (const std::exception& error) {
        log::warning("cannot play \"" + title + "\": " + error.what());
    }
    return 0;
}

void FeedbackService::TriggerFeedback(sdbus::Result<std::uint32_t>&& result, std::string app_id,
                                      std::string event,
                                      std::map<std::string, sdbus::Variant> hints,
                                      std::int32_t timeout) {
    // feedbackd's own checks, answered as feedbackd answers them.
    if (app_id.empty()) {
        result.returnError(invalid_args("Invalid app id " + app_id));
        return;
    }
    if (event.empty()) {
        result.returnError(invalid_args("Invalid event " + event));
        return;
    }
    feedback::Profile level = profile_;
    try {
        level = hinted_level(hints, profile_);
    } catch (const sdbus::Error& error) {
        result.returnError(error);
        return;
    }
    timeout = std::max(timeout, -1);
    const std::uint32_t id = next_id_++;
    if (next_id_ == 0) {
        next_id_ = 1;
    }
    const std::string sender = dbus::with_current_message(
        getObject(), [](const sdbus::Message& message) { return dbus::sender_of(message); });
    // The caller has its id before anything plays, as with feedbackd.
    result.returnResults(id);

    const ThemeEntry* entry = theme_.lookup(event, level);
    const std::uint64_t playback = entry ? play(*entry, event, timeout == -1 ? 0 : -1) : 0;
    const std::string about = "event " + std::to_string(id) + " \"" + event + "\" from " + app_id +
                              " (" + sender + "), " + std::string(to_string(level)) + ": ";
    if (playback == 0) {
        log::debug(about + "no feedback");
        emitFeedbackEnded(id, end_reason::not_found);
        return;
    }
    log::debug(about + "playback " + std::to_string(playback));
    Event& added = events_[id];
    added.sender = sender;
    added.level = theme_.level_of(event, level).value();
    added.playback = playback;
    if (timeout > 0) {
        added.expires_us = monotonic_now_us() + static_cast<std::uint64_t>(timeout) * 1'000'000;
        arm_expiry();
    }
}

void FeedbackService::EndFeedback(const std::uint32_t& id) {
    end(id, end_reason::explicit_end);
}

void FeedbackService::end(std::uint32_t id, std::uint32_t reason) {
    const auto event = events_.find(id);
    if (event == events_.end() || event->second.ending) {
        return;
    }
    event->second.end_reason = reason;
    event->second.ending = true;
    try {
        haptics_.Stop(event->second.playback);
        return;  // FeedbackEnded when vibscored reports the playback's end
    } catch (const sdbus::Error& error) {
        log::warning("vibscored did not stop playback " + std::to_string(event->second.playback) +
                     ": " + error.getName() + ": " + error.getMessage());
    }
    ended(event);
}

void FeedbackService::ended(std::map<std::uint32_t, Event>::iterator event) {
    const auto id = event->first;
    const auto reason = event->second.end_reason;
    events_.erase(event);
    emitFeedbackEnded(id, reason);
    arm_expiry();
}

void FeedbackService::end_where(const std::function<bool(const Event&)>& which,
                                std::uint32_t reason) {
    std::vector<std::uint32_t> ids;
    for (const auto& [id, event] : events_) {
        if (which(event)) {
            ids.push_back(id);
        }
    }
    for (const auto id : ids) {
        end(id, reason);
    }
}

void FeedbackService::playback_finished(std::uint64_t playback, const std::string& reason) {
    if (haptic_playback_ == playback) {
        haptic_playback_.reset();
    }
    const auto event = std::find_if(events_.begin(), events_.end(), [&](const auto& entry) {
        return entry.second.playback == playback;
    });
    if (event != events_.end()) {
        log::debug("event " + std::to_string(event->first) + ": playback " +
                   std::to_string(playback) + " " + reason);
        ended(event);
    }
}

void FeedbackService::haptics_gone() {
    log::warning("vibscored left the bus; the feedback it played has ended");
    haptic_playback_.reset();
    while (!events_.empty()) {
        ended(events_.begin());
    }
}

void FeedbackService::arm_expiry() {
    std::optional<std::uint64_t> earliest;
    for (const auto& [id, event] : events_) {
        if (event.expires_us && !event.ending) {
            earliest = std::min(earliest.value_or(*event.expires_us), *event.expires_us);
        }
    }
    if (earliest) {
        expiry_.arm(*earliest);
    } else {
        expiry_.disarm();
    }
}

void FeedbackService::expire() {
    const auto now = monotonic_now_us();
    end_where([&](const Event& event) { return event.expires_us && *event.expires_us <= now; },
              end_reason::expired);
    arm_expiry();
}

void FeedbackService::Profile(const std::string& value) {
    const auto profile = parse_profile(value);
    if (!profile) {
        throw invalid_args("unknown profile \"" + value + "\" (expected " +
                           std::string(kProfileNames) + ")");
    }
    if (*profile == profile_) {
        return;
    }
    profile_ = *profile;
    log::info("profile " + value);
    dbus::emit_properties_changed(getObject(), org::sigxcpu::Feedback_adaptor::INTERFACE_NAME,
                                  {"Profile"});
    // Feedback the new profile would not give ends now, as feedbackd ends it.
    end_where([&](const Event& event) { return event.level > profile_; }, end_reason::explicit_end);
    if (profile_ < feedback::Profile::quiet && haptic_playback_) {
        try {
            haptics_.Stop(*haptic_playback_);
        } catch (const sdbus::Error& error) {
            log::warning("vibscored did not stop the haptic pattern: " + error.getMessage());
        }
    }
}

bool FeedbackService::Vibrate(const std::string& app_id,
                              const std::vector<sdbus::Struct<double, std::uint32_t>>& pattern) {
    if (pattern.size() > kMaxPatternSteps) {
        throw invalid_args("the pattern has " + std::to_string(pattern.size()) +
                           " steps; at most " + std::to_string(kMaxPatternSteps) + " are allowed");
    }
    VibrationPattern steps;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        const double strength = pattern[i].get<0>();
        const std::uint32_t ms = pattern[i].get<1>();
        if (!(strength >= 0.0 && strength <= 1.0)) {
            throw invalid_args("step " + std::to_string(i + 1) + ": strength " +
                               std::to_string(strength) + " is outside 0..1");
        }
        if (ms > kMaxStepMs) {
            throw invalid_args("step " + std::to_string(i + 1) + ": " + std::to_string(ms) +
                               " ms is longer than " + std::to_string(kMaxStepMs) + " ms");
        }
        steps.push_back({ms / 1000.0, strength, strength, 0.0});
    }
    if (profile_ < feedback::Profile::quiet) {
        return false;
    }
    if (pattern_seconds(steps) <= 0.0) {
        if (haptic_playback_) {
            try {
                haptics_.Stop(*haptic_playback_);
            } catch (const sdbus::Error& error) {
                log::warning("vibscored did not stop the haptic pattern: " + error.getMessage());
            }
        }
        return true;
    }
    ThemeEntry entry;
    entry.pattern = std::move(steps);
    entry.usage = settings_.haptic_usage;
    const auto playback = play(entry, "haptic pattern of " + app_id, 0);
    if (playback != 0) {
        haptic_playback_ = playback;
    }
    return playback != 0;
}

}  // namespace vibscore::feedback
