#pragma once

#include <cairo.h>

#include <string>
#include <vector>

// Text in pictures: one face everywhere, and labels that fit the room they have, so no label
// runs into the next mark.
namespace vibscore::pictures {

// DejaVu Sans, `size` pixels high, bold or not.
void select_font(cairo_t* cairo, double size, bool bold);

// How far `text` advances the pen in the current font.
double text_width(cairo_t* cairo, const std::string& text);

// Shows `text` from the pen position (x, y) rounded to whole pixels: cairo versions place
// glyphs between pixels differently (1.16 rounds, 1.18 keeps quarters), but alike on a pixel.
void show_text_at(cairo_t* cairo, double x, double y, const std::string& text);

// Shows `text` with its ink centred on (x, y), to the nearest pixel.
void show_centred(cairo_t* cairo, double x, double y, const std::string& text);

// The first of `choices` (the most telling first) whose advance is at most `room`, or "".
std::string fitted_text(cairo_t* cairo, const std::vector<std::string>& choices, double room);

// `text` when it fits `room`, else as many of its first characters as fit before "…", or "" when
// not even "…" does.
std::string elided_text(cairo_t* cairo, const std::string& text, double room);

}  // namespace vibscore::pictures
