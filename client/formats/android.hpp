#pragma once

#include <string>
#include <string_view>

#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"

// Android's vibration formats (docs/formats.md):
// - VibrationEffect.createWaveform(timings, amplitudes, repeat) as JSON:
//   {"timings": [ms...], "amplitudes": [0..255...], "repeat": -1};
// - the XML VibrationEffect.parseFromXml reads: <vibration-effect> holding a <waveform-effect>
//   of <waveform-entry durationMs amplitude> (inside <repeating> when it loops), or a
//   <waveform-envelope-effect> of <control-point amplitude frequencyHz durationMs> ramps.
namespace vibscore::formats {

struct AndroidOptions {
    bool loop = false;  // repeat the whole pattern (repeat index 0, or <repeating>)
};

// One step per note at the note's own strength (a waveform has no ramps), a silent step for
// each gap; the steps add up to the piece's length.
std::string write_android_json(const SoundTrack& track, const AndroidOptions& options);
std::string write_android_xml(const SoundTrack& track, const AndroidOptions& options);

// Ramps of amplitude and frequency: hairpins and glides kept. Every note needs a frequency, so
// only scores on sine clefs can be written this way; throws std::invalid_argument otherwise.
std::string write_android_envelope(const SoundTrack& track, const AndroidOptions& options);

// Read onto the clef; a waveform has no pitch, so its notes go on string 1; an envelope's
// frequencies go to the nearest string of a sine clef, or keep their contour on another clef.
// One pass of a repeating pattern is read. Throw DocumentError with line and column.
ImportedScore read_android_json(std::string_view text, const std::string& file,
                                const ChosenClef& chosen);
ImportedScore read_android_xml(std::string_view text, const std::string& file,
                               const ChosenClef& chosen);

}  // namespace vibscore::formats
