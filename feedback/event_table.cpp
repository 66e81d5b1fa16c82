#include "feedback/event_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/log.hpp"
#include "common/quoted_text.hpp"

namespace vibscore::feedback {

std::vector<std::string> parse_app_id_list(const std::string& list) {
    std::vector<std::string> items;
    std::size_t start = 0;
    while (start <= list.size()) {
        const auto comma = std::min(list.find(',', start), list.size());
        if (comma > start) {
            items.push_back(list.substr(start, comma - start));
        }
        start = comma + 1;
    }
    return items;
}

std::string app_id_list(const std::vector<std::string>& app_ids) {
    std::string list;
    for (const auto& id : app_ids) {
        list += (list.empty() ? "" : ",") + id;
    }
    return list;
}

EventTable::EventTable(Haptics& haptics, Theme theme, FeedbackSettings settings,
                       Callbacks callbacks)
    : haptics_(haptics),
      theme_(std::move(theme)),
      settings_(std::move(settings)),
      callbacks_(std::move(callbacks)),
      profile_(settings_.profile) {}

std::uint32_t EventTable::new_id() {
    // In order from 1, skipping 0 and, after a wrap, the ids of events still playing.
    std::uint32_t id = 0;
    while (id == 0 || events_.contains(id)) {
        id = next_id_++;
    }
    return id;
}

Profile EventTable::level_for(const Trigger& trigger) const {
    const Profile wanted = trigger.profile_hint.value_or(Profile::full);
    // feedbackd's get_effective_level: an important event of an app allowed to send one plays
    // at the level it asks for (full unless hinted), whatever the profile; any other can only
    // lower the profile's level.
    if (trigger.important) {
        const auto& allowed = settings_.allow_important;
        if (std::find(allowed.begin(), allowed.end(), trigger.app_id) != allowed.end()) {
            return wanted;
        }
        log::debug("the \"important\" hint of " + quoted_text(trigger.app_id) +
                   " is ignored: it is not in allow-important");
    }
    return std::min(profile_, wanted);
}

void EventTable::trigger(std::uint32_t id, const Trigger& trigger, std::uint64_t now_us) {
    const Profile level = level_for(trigger);
    const std::string about = "event " + std::to_string(id) + " " + quoted_text(trigger.event) +
                              " from " + quoted_text(trigger.app_id) + " (" + trigger.sender +
                              "), " + std::string(to_string(level)) + ": ";
    const auto [played, entry_level] = play_for(trigger, level);
    if (played.playback == 0) {
        log::debug(about + "no feedback");
        callbacks_.feedback_ended(id, end_reason::not_found);
        return;
    }
    log::debug(about + "playback " + std::to_string(played.playback));
    Event& added = events_[id];
    added.sender = trigger.sender;
    added.level = entry_level;
    added.playback = played.playback;
    if (trigger.timeout > 0) {
        added.expires_us = now_us + static_cast<std::uint64_t>(trigger.timeout) * 1'000'000;
        update_expiry();
    }
}

EventTable::Chosen EventTable::play_for(const Trigger& trigger, Profile level) {
    const int repeat = trigger.timeout == -1 ? 0 : -1;
    const ThemeEntry* entry = theme_.lookup(trigger.event, level);
    const auto theme_level = theme_.level_of(trigger.event, level);
    const auto mine = user_scores_.find(trigger.event);
    const bool in_theme = theme_.events().contains(trigger.event);
    if (mine != user_scores_.end() && (in_theme ? entry != nullptr : level >= Profile::quiet)) {
        ThemeEntry chosen;
        chosen.score = mine->second;
        chosen.usage = entry != nullptr ? entry->usage : usage_for_event(trigger.event);
        const auto played =
            haptics_.play({chosen, trigger.event, repeat, settings_.max_haptic_strength});
        if (!played.unknown_score) {
            return {played, theme_level.value_or(Profile::quiet)};
        }
        log::warning("the score " + quoted_text(mine->second) + " chosen for " +
                     quoted_text(trigger.event) +
                     " is not in vibscored's registry: the theme's plays instead");
    }
    if (entry == nullptr) {
        return {};
    }
    return {haptics_.play({*entry, trigger.event, repeat, settings_.max_haptic_strength}),
            *theme_level};
}

bool EventTable::set_user_scores(UserScores scores) {
    if (scores == user_scores_) {
        return false;
    }
    user_scores_ = std::move(scores);
    return true;
}

std::vector<EventScore> EventTable::event_scores() const {
    std::map<std::string, EventScore> events;
    for (const auto& [event, levels] : theme_.events()) {
        if (const ThemeEntry* entry = theme_.lookup(event, Profile::full)) {
            events[event] = {event, entry->score, entry->score, false};
        }
    }
    for (const auto& [event, score] : user_scores_) {
        auto& listed = events[event];
        listed.event = event;
        listed.score = score;
        listed.assigned = true;
    }
    std::vector<EventScore> list;
    for (auto& [event, score] : events) {
        list.push_back(std::move(score));
    }
    return list;
}

void EventTable::end(std::uint32_t id, const std::string& sender) {
    const auto event = events_.find(id);
    if (event == events_.end()) {
        log::debug("EndFeedback(" + std::to_string(id) + ") from " + sender +
                   ": not playing, ignored");
        return;
    }
    if (event->second.sender != sender) {
        // feedbackd ties feedback to its sender: no client ends another's.
        log::debug("EndFeedback(" + std::to_string(id) + ") from " + sender + ": the event is " +
                   event->second.sender + "'s, ignored");
        return;
    }
    end_event(event, end_reason::explicit_end);
}

void EventTable::end_event(Events::iterator event, std::uint32_t reason) {
    if (event->second.ending) {
        return;
    }
    event->second.end_reason = reason;
    event->second.ending = true;
    if (haptics_.stop(event->second.playback)) {
        update_expiry();
        return;  // FeedbackEnded when vibscored reports the playback's end
    }
    ended(event);
}

void EventTable::ended(Events::iterator event) {
    const auto id = event->first;
    const auto reason = event->second.end_reason;
    events_.erase(event);
    callbacks_.feedback_ended(id, reason);
    update_expiry();
}

void EventTable::end_where(const std::function<bool(const Event&)>& which, std::uint32_t reason) {
    std::vector<std::uint32_t> ids;
    for (const auto& [id, event] : events_) {
        if (which(event)) {
            ids.push_back(id);
        }
    }
    for (const auto id : ids) {
        if (const auto event = events_.find(id); event != events_.end()) {
            end_event(event, reason);
        }
    }
}

bool EventTable::vibrate(const std::string& sender, const std::string& app_id,
                         const std::vector<HapticStep>& pattern) {
    std::vector<VibraStep> steps;
    for (std::size_t i = 0; i < std::min(pattern.size(), kMaxPatternSteps); ++i) {
        if (std::isnan(pattern[i].strength)) {
            throw std::invalid_argument("step " + std::to_string(i + 1) +
                                        ": the strength is not a number");
        }
        steps.push_back(
            {std::clamp(pattern[i].strength, 0.0, 1.0), std::min(pattern[i].ms, kMaxStepMs)});
    }
    if (pattern.size() > kMaxPatternSteps) {
        log::debug("the pattern of " + quoted_text(app_id) + " has " +
                   std::to_string(pattern.size()) + " steps: its first " +
                   std::to_string(kMaxPatternSteps) + " play, as feedbackd plays them");
    }
    if (profile_ < Profile::quiet) {
        return false;
    }
    auto feedback = pattern_feedback(std::move(steps));
    // A new pattern replaces the caller's own, never another client's.
    stop_pattern_of(sender);
    if (feedback.duration_ms == 0) {
        return true;
    }
    ThemeEntry entry;
    entry.vibra = std::move(feedback);
    entry.usage = settings_.haptic_usage;
    const auto played =
        // The app id in the score's title as the log shows it: bounded, no control characters.
        haptics_.play(
            {entry, "haptic pattern of " + quoted_text(app_id), 0, settings_.max_haptic_strength});
    if (played.playback != 0) {
        patterns_[sender] = played.playback;
    }
    return played.playback != 0;
}

void EventTable::stop_pattern_of(const std::string& sender) {
    const auto pattern = patterns_.find(sender);
    if (pattern != patterns_.end()) {
        haptics_.stop(pattern->second);
        patterns_.erase(pattern);
    }
}

bool EventTable::set_profile(Profile profile) {
    if (profile == profile_) {
        return false;
    }
    profile_ = profile;
    log::info("profile " + std::string(to_string(profile)));
    // Feedback the new profile would not give ends now, as feedbackd ends it.
    end_where([&](const Event& event) { return event.level > profile_; }, end_reason::explicit_end);
    if (profile_ < Profile::quiet) {
        while (!patterns_.empty()) {
            stop_pattern_of(patterns_.begin()->first);
        }
    }
    return true;
}

void EventTable::set_max_haptic_strength(double strength) {
    settings_.max_haptic_strength = std::clamp(strength, 0.0, 1.0);
}

void EventTable::set_allow_important(std::vector<std::string> app_ids) {
    settings_.allow_important = std::move(app_ids);
}

void EventTable::expire(std::uint64_t now_us) {
    end_where([&](const Event& event) { return event.expires_us && *event.expires_us <= now_us; },
              end_reason::expired);
    // The timer that called this has fired: it is armed again whatever the earliest is now.
    update_expiry(true);
}

void EventTable::playback_finished(std::uint64_t playback) {
    std::erase_if(patterns_, [&](const auto& pattern) { return pattern.second == playback; });
    const auto event = std::find_if(events_.begin(), events_.end(), [&](const auto& entry) {
        return entry.second.playback == playback;
    });
    if (event != events_.end()) {
        log::debug("event " + std::to_string(event->first) + ": playback " +
                   std::to_string(playback) + " ended");
        ended(event);
    }
}

void EventTable::haptics_gone() {
    if (!events_.empty() || !patterns_.empty()) {
        log::warning("vibscored left the bus; the feedback it played has ended");
    }
    patterns_.clear();
    while (!events_.empty()) {
        ended(events_.begin());
    }
}

void EventTable::sender_left(const std::string& sender) {
    end_where([&](const Event& event) { return event.sender == sender; }, end_reason::explicit_end);
    stop_pattern_of(sender);
}

void EventTable::update_expiry(bool always) {
    std::optional<std::uint64_t> earliest;
    for (const auto& [id, event] : events_) {
        if (event.expires_us && !event.ending) {
            earliest = std::min(earliest.value_or(*event.expires_us), *event.expires_us);
        }
    }
    if (always || earliest != reported_expiry_) {
        reported_expiry_ = earliest;
        if (callbacks_.expiry_changed) {
            callbacks_.expiry_changed(earliest);
        }
    }
}

}  // namespace vibscore::feedback
