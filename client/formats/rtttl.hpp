#pragma once

#include <string>
#include <string_view>

#include "client/formats/score_builder.hpp"

// RTTTL, the Nokia ringtone text: "name:d=4,o=5,b=125:8c6,8e6,p,4.g6" (docs/formats.md).
namespace vibscore::formats {

// Reads the melody onto the clef: each note's duration and dot become its length, pauses
// rests, the bpm the tempo (a copy of the clef when it differs), the pitches strings by their
// contour (strings_by_contour), and every note takes the clef's strongest number.
// Throws DocumentError naming the line and column of each problem.
ImportedScore read_rtttl(std::string_view text, const std::string& file, const ChosenClef& chosen);

}  // namespace vibscore::formats
