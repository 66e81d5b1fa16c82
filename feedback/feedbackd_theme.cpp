#include "feedback/feedbackd_theme.hpp"

#include <algorithm>

namespace vibscore::feedback {

namespace {

constexpr double kRumbleStrength = 32768.0 / 65535.0;  // feedbackd's strong_magnitude 0x8000
constexpr unsigned kPeriodicFull = 0x7fff;             // a periodic effect's full magnitude
constexpr unsigned kDefaultDurationMs = 1000;          // FBD_FEEDBACK_VIBRA_DEFAULT_DURATION
constexpr long kMaxMs = 3'600'000;                     // a score lasts at most an hour

unsigned milliseconds(const JsonFields& json, const JsonValue& at, const char* key,
                      unsigned fallback) {
    const JsonValue* value = at.find(key);
    return value != nullptr ? static_cast<unsigned>(json.integer(*value, 0, kMaxMs)) : fallback;
}

ThemeEntry vibra_entry(const JsonFields& json, const JsonValue& at, const std::string& type,
                       const std::string& event) {
    ThemeEntry entry;
    entry.usage = usage_for_event(event);
    const unsigned duration = milliseconds(json, at, "duration", kDefaultDurationMs);
    if (type == "VibraRumble") {
        json.only_members(at, {"event-name", "type", "duration", "count", "pause"});
        const JsonValue* count = at.find("count");
        entry.pattern = rumble_pattern(
            duration,
            count != nullptr ? static_cast<unsigned>(json.integer(*count, 1, 1'000'000)) : 1u,
            milliseconds(json, at, "pause", 0));
    } else {
        json.only_members(
            at, {"event-name", "type", "duration", "magnitude", "fade-in-time", "fade-in-level"});
        const auto level = [&](const char* key) {
            const JsonValue* value = at.find(key);
            return value != nullptr ? static_cast<unsigned>(json.integer(*value, 0, kPeriodicFull))
                                    : 0u;
        };
        entry.pattern = periodic_pattern(duration, level("magnitude"), level("fade-in-level"),
                                         milliseconds(json, at, "fade-in-time", 0));
    }
    return entry;
}

}  // namespace

VibrationPattern rumble_pattern(unsigned duration_ms, unsigned count, unsigned pause_ms) {
    count = std::max(count, 1u);
    unsigned rumble_ms = duration_ms / count;
    if (rumble_ms <= pause_ms) {
        rumble_ms = kDefaultDurationMs;
        pause_ms = 0;
        count = 1;
    } else {
        rumble_ms -= pause_ms;
    }
    VibrationPattern pattern;
    for (unsigned i = 0; i < count; ++i) {
        pattern.push_back({rumble_ms / 1000.0, kRumbleStrength, kRumbleStrength, 0.0});
        if (pause_ms > 0) {
            pattern.push_back({pause_ms / 1000.0, 0.0, 0.0, 0.0});
        }
    }
    return pattern;
}

VibrationPattern periodic_pattern(unsigned duration_ms, unsigned magnitude, unsigned fade_in_level,
                                  unsigned fade_in_time_ms) {
    // feedbackd's defaults (fbd_dev_vibra_periodic): full strength, no fade.
    if (magnitude == 0) {
        magnitude = kPeriodicFull;
    }
    if (fade_in_level == 0) {
        fade_in_level = magnitude;
    }
    if (fade_in_time_ms == 0) {
        fade_in_time_ms = duration_ms;
    }
    const double strength = static_cast<double>(std::min(magnitude, kPeriodicFull)) / kPeriodicFull;
    const double start =
        static_cast<double>(std::min(fade_in_level, kPeriodicFull)) / kPeriodicFull;
    const unsigned fade_ms = std::min(fade_in_time_ms, duration_ms);
    VibrationPattern pattern;
    if (fade_ms > 0) {
        pattern.push_back({fade_ms / 1000.0, start, strength, 0.0});
    }
    if (duration_ms > fade_ms) {
        pattern.push_back({(duration_ms - fade_ms) / 1000.0, strength, strength, 0.0});
    }
    return pattern;
}

Theme read_feedbackd_theme(const JsonFields& json) {
    const JsonValue& root = json.document().root();
    json.only_members(root, {"name", "profiles"});
    Theme theme;
    theme.name = json.string(json.member(root, "name"));
    for (const auto& profile_at : json.array(json.member(root, "profiles")).items) {
        json.only_members(profile_at, {"name", "feedbacks"});
        const JsonValue& name = json.member(profile_at, "name");
        const auto profile_name = json.string(name);
        const auto profile = parse_profile(profile_name);
        if (!profile) {
            throw json.error(name, "unknown profile \"" + profile_name + "\" (expected " +
                                       std::string(kProfileNames) + ")");
        }
        for (const auto& at : json.array(json.member(profile_at, "feedbacks")).items) {
            json.object(at);
            const auto event = json.string(json.member(at, "event-name"));
            const JsonValue& type_at = json.member(at, "type");
            const auto type = json.string(type_at);
            if (type == "Sound" || type == "Led" || type == "Dummy") {
                continue;
            }
            if (type != "VibraRumble" && type != "VibraPeriodic") {
                throw json.error(type_at, "unknown feedback type \"" + type +
                                              "\" (expected Sound, Led, Dummy, "
                                              "VibraRumble or VibraPeriodic)");
            }
            auto entry = vibra_entry(json, at, type, event);
            // feedbackd plays one vibra feedback at a time: the first of an event's is it.
            const auto known = theme.events().find(event);
            if (known == theme.events().end() || !known->second.contains(*profile)) {
                theme.add(*profile, event, std::move(entry));
            }
        }
    }
    return theme;
}

}  // namespace vibscore::feedback
