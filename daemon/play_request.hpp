#pragma once

#include <sdbus-c++/Types.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "daemon/device_clefs.hpp"
#include "daemon/player.hpp"
#include "daemon/registry/registry.hpp"
#include "daemon/usage.hpp"
#include "score/bundle.hpp"

// The pure part of Play: the caller's options checked, the score it names found, and that score
// turned into what the player runs. No bus and no device, so every rule is reachable from a unit
// test; the bus service only adds who is calling.
namespace vibscore::daemon {

// A playback's cues are kept in memory; this bounds that memory for one hour of dense shapes.
inline constexpr std::size_t kMaxCues = 2'000'000;

// Play's options dictionary (a{sv}), checked. dbus/org.vibscore.Haptics1.xml documents each.
struct PlayOptions {
    Usage usage = Usage::notification;
    int repeat = 0;        // 0 once, n more times, -1 until stopped
    double intensity = 1;  // 0..1
    std::string clef;      // a registry clef every bar plays through; empty: the score's own
    std::uint32_t start_bar = 0;
};

// Throws RequestError (invalid) naming the option for an unknown key, a value of the wrong
// D-Bus type, or a value out of range.
PlayOptions parse_play_options(const std::map<std::string, sdbus::Variant>& options);

// The score Play names, ready to render.
struct ScoreToPlay {
    ScoreBundle bundle;
    std::string label;  // registry name, or "<inline>"
};

// `score` is a registry name or, when it starts with '<', a whole VibScore document. A clef
// override replaces every clef the score declares; without one, each declared clef plays
// through its device clef (vibscored.conf [clefs]). Throws RegistryError (not_found,
// invalid_document, limit_exceeded) as the registry does; a missing override clef is not_found
// before anything else is looked at.
ScoreToPlay find_score_to_play(const Registry& registry, const std::string& score,
                               const std::string& clef_override,
                               const DeviceClefs& device_clefs = {});

// The player's request: the score's cue schedule from the start bar, with the caller's usage,
// repeat and intensity (owner and sender are the caller's, for the bus service to fill in).
// Throws RequestError: invalid for a start bar past the last bar, limit_exceeded for a score
// needing more than kMaxCues actuator commands.
PlaybackRequest make_playback_request(const ScoreToPlay& score, const PlayOptions& options,
                                      double separation_s);

}  // namespace vibscore::daemon
