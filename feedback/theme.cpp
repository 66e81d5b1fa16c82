#include "feedback/theme.hpp"

#include "common/usage.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/json_fields.hpp"

namespace vibscore::feedback {

namespace {

constexpr const char* kFormatKey = "vibscore-theme";

// vibscore's theme format (docs/feedbackd.md):
//   { "vibscore-theme": 1, "name": "default",
//     "profiles": { "quiet": { "EVENT": { "score": "NAME", "usage": "touch",
//                                          "intensity": 0.8, "clef": "NAME" }, ... }, ... } }
Theme read_vibscore_theme(const JsonFields& json) {
    const JsonValue& root = json.document().root();
    json.only_members(root, {kFormatKey, "name", "profiles"});
    json.integer(json.member(root, kFormatKey), 1, 1);
    Theme theme;
    theme.name = json.string(json.member(root, "name"));
    for (const auto& [profile_name, profile_offset, events] :
         json.object(json.member(root, "profiles")).members) {
        const auto profile = parse_profile(profile_name);
        if (!profile) {
            throw DocumentError(json.document().where(profile_offset),
                                "unknown profile \"" + profile_name + "\" (expected " +
                                    std::string(kProfileNames) + ")");
        }
        for (const auto& [event, event_offset, at] : json.object(events).members) {
            json.only_members(at, {"score", "usage", "intensity", "clef"});
            ThemeEntry entry;
            const JsonValue& score = json.member(at, "score");
            entry.score = json.string(score);
            if (entry.score.empty()) {
                throw json.error(score, "the score name is empty");
            }
            const JsonValue* usage = at.find("usage");
            entry.usage = usage != nullptr ? json.string(*usage) : usage_for_event(event);
            if (!daemon::parse_usage(entry.usage)) {
                throw json.error(*usage, "unknown usage \"" + entry.usage + "\" (expected " +
                                             std::string(daemon::usage_names()) + ")");
            }
            if (const JsonValue* intensity = at.find("intensity")) {
                entry.intensity = json.number(*intensity, 0.0, 1.0);
            }
            if (const JsonValue* clef = at.find("clef")) {
                entry.clef = json.string(*clef);
            }
            theme.add(*profile, event, std::move(entry));
        }
    }
    return theme;
}

}  // namespace

const ThemeEntry* Theme::lookup(std::string_view event, Profile profile) const {
    const auto level = level_of(event, profile);
    return level ? &events_.find(event)->second.at(*level) : nullptr;
}

std::optional<Profile> Theme::level_of(std::string_view event, Profile profile) const {
    const auto found = events_.find(event);
    if (found == events_.end()) {
        return std::nullopt;
    }
    // The highest defined level not above the profile.
    const auto above = found->second.upper_bound(profile);
    if (above == found->second.begin()) {
        return std::nullopt;
    }
    return std::prev(above)->first;
}

void Theme::add(Profile profile, const std::string& event, ThemeEntry entry) {
    events_[event][profile] = std::move(entry);
}

Theme parse_theme(const JsonDocument& document, const ThemeSearch& search) {
    const JsonFields json(document);
    if (document.root().kind != JsonValue::Kind::object) {
        throw json.error(document.root(), "a theme is a JSON object");
    }
    if (document.root().find(kFormatKey) != nullptr) {
        return read_vibscore_theme(json);
    }
    return expand_feedbackd_theme(read_feedbackd_theme_file(json), search);
}

Theme load_theme(const std::string& path, const ThemeSearch& search) {
    return parse_theme(read_json_file(path), search);
}

std::string usage_for_event(std::string_view event) {
    if (event == "phone-incoming-call") {
        return "ringtone";
    }
    if (event == "alarm-clock-elapsed") {
        return "alarm";
    }
    // The user's own actions: presses, closing windows, a message going out.
    for (const std::string_view prefix : {"button-", "window-", "message-sent-"}) {
        if (event.starts_with(prefix)) {
            return "touch";
        }
    }
    return "notification";
}

}  // namespace vibscore::feedback
