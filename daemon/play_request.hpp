#pragma once

#include <sdbus-c++/Types.h>

#include <cstdint>
#include <map>
#include <string>

#include "common/usage.hpp"
#include "daemon/device_clefs.hpp"
#include "daemon/player.hpp"
#include "daemon/registry/registry.hpp"
#include "score/bundle.hpp"

// The pure part of Play: the caller's options checked, the score it names found, and that score
// turned into what the player runs. No bus and no device, so every rule is reachable from a unit
// test; the bus service only adds who is calling.
namespace vibscore::daemon {

// Play's options dictionary (a{sv}), checked. dbus/org.vibscore.Haptics1.xml documents each.
struct PlayOptions {
    Usage usage = Usage::notification;
    int repeat = 0;        // 0 once, n more times, -1 until stopped
    double intensity = 1;  // 0..1
    std::string clef;      // a registry clef every bar plays through; empty: the score's own
    // VibClef documents sent along with an inline score, by the href that names each.
    std::map<std::string, std::string> clef_documents;
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

// `score` is a registry name or, when it starts with '<', a whole VibScore document, whose clefs
// are the documents sent along with it (options.clef_documents) or the registry's. A clef
// override (options.clef) replaces every clef the score declares; without one, each clef the
// score names from the registry plays through its device clef (vibscored.conf [clefs]); clefs
// sent along with the score play as sent: they are the caller's choice, as an override is.
// Throws RegistryError (not_found, invalid_document, limit_exceeded) as the registry does,
// RequestError (invalid) for clef documents sent with a registry name.
// With `fit_cache`, clefs fitted to the actuator are looked up and kept there.
ScoreToPlay find_score_to_play(const Registry& registry, const std::string& score,
                               const PlayOptions& options, const DeviceClefs& device_clefs = {},
                               ClefFitCache* fit_cache = nullptr);

// The bytes of the documents a Play carries, its cost at admission (admission.hpp): the inline
// score's and each clef document sent along; 0 for a registry score's name. Counted, not read.
std::size_t document_bytes(const std::string& score, const PlayOptions& options);
// The same from Play's options as they came over the bus, before they are checked: "clefs" counts
// when it is a dictionary of strings.
std::size_t document_bytes(const std::string& score,
                           const std::map<std::string, sdbus::Variant>& options);

// The player's request: the score performed from the start bar, whose cues the player reads as
// it plays them, with the caller's usage, repeat and intensity (owner and sender are the
// caller's, for the bus service to fill in). Throws RequestError (invalid) for a start bar past
// the last bar.
PlaybackRequest make_playback_request(const ScoreToPlay& score, const PlayOptions& options,
                                      double separation_s);

}  // namespace vibscore::daemon
