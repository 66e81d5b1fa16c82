#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "client/editor/position.hpp"
#include "score/score.hpp"

// The staff of thesis Fig. 4.1 as a grid of terminal cells, one row per line of the drawing.
// Both `vibscore show` (ANSI text) and the editor (ncurses) paint this grid; neither draws the
// staff itself.
namespace vibscore::editor {

// What a cell shows, so each painter can colour it its own way.
enum class Ink : std::uint8_t {
    blank,
    line,     // staff lines and bar lines
    head,     // a note head (its number) and its dot
    sustain,  // the line after a head that shows how long the note lasts
    rest,
    dynamics,    // crescendo < and decrescendo > hairpins
    tie,         // legato and portamento marks
    length,      // the length written under a symbol: 4 = quarter, 8. = dotted 8th
    clef_fewer,  // a bar's clef box: fewer than four beats (cyan in the thesis)
    clef_exact,  // exactly four (white)
    clef_more,   // more than four (magenta)
    playback,    // the playback cursor
    mark,  // under the staff: the editing cursor's ▲ (and what it is doing), the block's ═
};

// Marks laid over the ink.
enum Overlay : std::uint8_t {
    overlay_none = 0,
    overlay_cursor_column = 1,  // the editing cursor's column on the staff
    overlay_cursor = 2,         // the cursor's cell on the active string
    overlay_selected = 4,       // inside the block
    overlay_playing = 8,        // the symbol being played
};

struct Cell {
    std::string glyph = " ";  // one terminal column of UTF-8
    Ink ink = Ink::blank;
    std::uint8_t overlay = overlay_none;
    bool operator==(const Cell&) const = default;
};

// Rows from the top: the clef box with the bar's beat count, the dynamics, the six strings
// (string 6, the highest pitch, on top), ties, lengths, and the marks row: the playback
// cursor, the editing cursor and the block, drawn as glyphs so a monochrome terminal (or a
// capture of the screen) shows them too.
enum StaffRow : int {
    row_clef = 0,
    row_dynamics = 1,
    row_top_string = 2,
    row_ties = 8,
    row_lengths = 9,
    row_playback = 10,  // the marks row
    staff_rows = 11,
};
constexpr int row_of_string(int string) {
    return row_top_string + (6 - string);
}

// Where each part of the score landed, in columns.
struct Span {
    enum class Kind { bar_line, symbol, end };  // end: the empty position closing a bar
    Kind kind = Kind::symbol;
    std::size_t bar = 0, symbol = 0;
    int x = 0, width = 1;
};

struct LayoutOptions {
    bool end_positions = false;  // the editor shows the empty position at the end of each bar
    std::optional<Position> cursor;
    int cursor_string = 1;
    std::optional<Block> block;
    std::optional<Position> playing;
    // The proposal still being entered: drawn, but not counted in its bar's beats until it is
    // entered (a newcomer read a full bar while the last note was only proposed). Not set for
    // a symbol being changed, which the bar holds (staff_options.hpp).
    std::optional<Position> entering;
    // Written after the cursor's ▲: what the open symbol is ("new", "change").
    std::string cursor_label;
};

struct StaffLayout {
    int width = 0;
    std::vector<std::vector<Cell>> rows;  // staff_rows rows of `width` cells
    std::vector<Span> spans;

    // The column of a position's symbol (its head), or of a bar's end position; -1 if not shown.
    int x_of(Position at) const;
};

StaffLayout layout_staff(const Score& score, const LayoutOptions& options = {});

// Columns a symbol takes: longer lengths are wider, so durations show at a glance.
int symbol_width(const Symbol& symbol);
// The length as written under a symbol: "1" whole, "2." dotted half, "4" quarter ... "32".
std::string length_label(Length length);
// A bar's beat count as printed in its clef box: 4, 3.5, 0.375.
std::string beat_label(double beats);

// The first column to show in a window `width` wide so `x` stays inside it with a margin,
// moving as little as possible from `first`.
int scroll_to_show(int first, int width, int x, int total_width);

// Column ranges [begin, end) at most `width` wide that break the staff at bar lines, for
// printing a long score as several systems.
std::vector<std::pair<int, int>> systems(const StaffLayout& layout, int width);

}  // namespace vibscore::editor
