#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "client/formats/score_builder.hpp"
#include "score/bundle.hpp"

// Scores as Standard MIDI Files (docs/formats.md).
namespace vibscore::formats {

// The pitches vibscore writes strings 1..6 as: C4 D4 E4 F4 G4 A4 (MIDI 60 62 64 65 67 69).
inline constexpr int midi_string_pitches[] = {60, 62, 64, 65, 67, 69};

// A format 0 file, 480 ticks per quarter note: each note at its written length with velocity
// from its strength, a tempo event wherever a bar's clef changes the tempo.
std::string write_midi(const ScoreBundle& bundle);

// Reads one track (1-based; by default the first with notes) onto the clef: one voice (of notes
// starting together the highest; a new note cuts a sounding one short), lengths on the 32nd-note
// grid, a clef per tempo, velocity to the nearest number, pitches to strings by contour (or
// string for string when they all are vibscore's six string pitches).
// Throws DocumentError naming the byte where the file goes wrong.
ImportedScore read_midi(std::string_view bytes, const std::string& file, const ChosenClef& chosen,
                        std::optional<int> track);

}  // namespace vibscore::formats
