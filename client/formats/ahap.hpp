#pragma once

#include <string>
#include <string_view>

#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"

// Apple Core Haptics' AHAP (docs/formats.md): each note a HapticContinuous event with
// HapticIntensity (strength) and HapticSharpness (the string's staff position), hairpins and
// glides as HapticIntensityControl and HapticSharpnessControl parameter curves.
namespace vibscore::formats {

// Apple caps a continuous event at 30 seconds; longer notes are written as several events.
inline constexpr double ahap_max_event_s = 30.0;

std::string write_ahap(const SoundTrack& track);

// Reads the haptic events and curves of an AHAP file (audio events are skipped) onto the clef.
// Throws DocumentError listing every problem at its line and column.
ImportedScore read_ahap(std::string_view text, const std::string& file, const ChosenClef& chosen);

}  // namespace vibscore::formats
