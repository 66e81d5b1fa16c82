#include "feedback/theme.hpp"

#include "daemon/usage.hpp"
#include "feedback/feedbackd_theme.hpp"

namespace vibscore::feedback {

namespace {

using Pointer = nlohmann::json::json_pointer;

constexpr const char* kFormatKey = "vibscore-theme";

// vibscore's theme format (docs/feedbackd.md):
//   { "vibscore-theme": 1, "name": "default",
//     "profiles": { "quiet": { "EVENT": { "score": "NAME", "usage": "touch",
//                                          "intensity": 0.8, "clef": "NAME" }, ... }, ... } }
Theme read_vibscore_theme(const JsonDocument& document) {
    const Pointer root;
    document.only_members(root, {kFormatKey, "name", "profiles"});
    if (document.integer(root / kFormatKey, 1, 1) != 1) {
        throw document.error(root / kFormatKey, "unknown theme format version");
    }
    Theme theme;
    theme.name = document.string(root / "name");
    for (const auto& [profile_name, events] : document.object(root / "profiles").items()) {
        const Pointer profile_at = root / "profiles" / profile_name;
        const auto profile = parse_profile(profile_name);
        if (!profile) {
            throw document.error(profile_at, "unknown profile \"" + profile_name + "\" (expected " +
                                                 std::string(kProfileNames) + ")");
        }
        for (const auto& [event, entry_json] : document.object(profile_at).items()) {
            const Pointer at = profile_at / event;
            document.only_members(at, {"score", "usage", "intensity", "clef"});
            ThemeEntry entry;
            entry.score = document.string(at / "score");
            if (entry.score.empty()) {
                throw document.error(at / "score", "the score name is empty");
            }
            entry.usage =
                document.has(at / "usage") ? document.string(at / "usage") : usage_for_event(event);
            if (!daemon::parse_usage(entry.usage)) {
                throw document.error(at / "usage", "unknown usage \"" + entry.usage +
                                                       "\" (expected " +
                                                       std::string(daemon::usage_names()) + ")");
            }
            if (document.has(at / "intensity")) {
                entry.intensity = document.number(at / "intensity", 0.0, 1.0);
            }
            if (document.has(at / "clef")) {
                entry.clef = document.string(at / "clef");
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

Theme parse_theme(const JsonDocument& document) {
    if (!document.root().is_object()) {
        throw document.error(Pointer(), "a theme is a JSON object");
    }
    return document.root().contains(kFormatKey) ? read_vibscore_theme(document)
                                                : read_feedbackd_theme(document);
}

Theme load_theme(const std::string& path) {
    return parse_theme(read_json_file(path));
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
