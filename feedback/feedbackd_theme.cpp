#include "feedback/feedbackd_theme.hpp"

#include <algorithm>

namespace vibscore::feedback {

namespace {

using Pointer = nlohmann::json::json_pointer;

constexpr double kRumbleStrength = 32768.0 / 65535.0;  // feedbackd's strong_magnitude 0x8000
constexpr unsigned kPeriodicFull = 0x7fff;             // a periodic effect's full magnitude
constexpr unsigned kDefaultDurationMs = 1000;          // FBD_FEEDBACK_VIBRA_DEFAULT_DURATION
constexpr long kMaxMs = 3'600'000;                     // a score lasts at most an hour

unsigned milliseconds(const JsonDocument& document, const Pointer& at, unsigned fallback) {
    return document.has(at) ? static_cast<unsigned>(document.integer(at, 0, kMaxMs)) : fallback;
}

ThemeEntry vibra_entry(const JsonDocument& document, const Pointer& at, const std::string& type,
                       const std::string& event) {
    ThemeEntry entry;
    entry.usage = usage_for_event(event);
    const unsigned duration = milliseconds(document, at / "duration", kDefaultDurationMs);
    if (type == "VibraRumble") {
        document.only_members(at, {"event-name", "type", "duration", "count", "pause"});
        const auto count =
            document.has(at / "count") ? document.integer(at / "count", 1, 1'000'000) : 1;
        entry.pattern = rumble_pattern(duration, static_cast<unsigned>(count),
                                       milliseconds(document, at / "pause", 0));
    } else {
        document.only_members(
            at, {"event-name", "type", "duration", "magnitude", "fade-in-time", "fade-in-level"});
        const auto level = [&](const char* key) {
            return document.has(at / key)
                       ? static_cast<unsigned>(document.integer(at / key, 0, kPeriodicFull))
                       : 0u;
        };
        entry.pattern = periodic_pattern(duration, level("magnitude"), level("fade-in-level"),
                                         milliseconds(document, at / "fade-in-time", 0));
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

Theme read_feedbackd_theme(const JsonDocument& document) {
    const Pointer root;
    document.only_members(root, {"name", "profiles"});
    Theme theme;
    theme.name = document.string(root / "name");
    const auto& profiles = document.array(root / "profiles");
    for (std::size_t p = 0; p < profiles.size(); ++p) {
        const Pointer profile_at = root / "profiles" / p;
        document.only_members(profile_at, {"name", "feedbacks"});
        const auto profile_name = document.string(profile_at / "name");
        const auto profile = parse_profile(profile_name);
        if (!profile) {
            throw document.error(profile_at / "name", "unknown profile \"" + profile_name +
                                                          "\" (expected " +
                                                          std::string(kProfileNames) + ")");
        }
        const auto& feedbacks = document.array(profile_at / "feedbacks");
        for (std::size_t f = 0; f < feedbacks.size(); ++f) {
            const Pointer at = profile_at / "feedbacks" / f;
            document.object(at);
            const auto event = document.string(at / "event-name");
            const auto type = document.string(at / "type");
            if (type == "Sound" || type == "Led" || type == "Dummy") {
                continue;
            }
            if (type != "VibraRumble" && type != "VibraPeriodic") {
                throw document.error(at / "type", "unknown feedback type \"" + type +
                                                      "\" (expected Sound, Led, Dummy, "
                                                      "VibraRumble or VibraPeriodic)");
            }
            auto entry = vibra_entry(document, at, type, event);
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
