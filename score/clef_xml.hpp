#pragma once

#include <string>
#include <string_view>

#include "score/clef.hpp"

namespace vibscore {

// Reads a VibClef document (thesis Table 3.2, §3.2): type, Tempo, Numbers, Strings with a
// frequency (sine) or Points (curve, line). Throws DocumentError listing every problem with its
// line and column.
Clef read_clef(std::string_view text, const std::string& file);

// Writes a VibClef document that read_clef reads back to an equal Clef.
std::string write_clef(const Clef& clef);

}  // namespace vibscore
