#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "client/editor/position.hpp"
#include "score/score.hpp"

// The edits the editor makes to a score, as plain functions of the score. Every function takes
// positions that are valid in the score it is given.
namespace vibscore::editor {

inline constexpr int lowest_string = 1;
inline constexpr int highest_string = 6;
inline constexpr int lowest_number = 1;
inline constexpr int highest_number = 9;
// A bar is full at four beats: the clef box is cyan below, white at and magenta above it
// (thesis Fig. 4.1).
inline constexpr double beats_in_a_full_bar = 4.0;

enum class Tie { legato, portamento };

std::int64_t& serial(Note& note, Tie tie);
std::int64_t serial(const Note& note, Tie tie);

// The end of a bar or a Blank: where a new symbol can go without moving another.
bool is_empty_position(const Score& score, Position at);
const Symbol* symbol_at(const Score& score, Position at);
Symbol* symbol_at(Score& score, Position at);
Note* note_at(Score& score, Position at);
const Note* note_at(const Score& score, Position at);

// The nearest note or rest before / after `at`, skipping Blanks and crossing bar lines.
std::optional<Position> symbol_before(const Score& score, Position at);
std::optional<Position> symbol_after(const Score& score, Position at);

// The positions of the symbols (Blanks included) in a block.
std::vector<Position> symbols_in(const Score& score, const Block& block);

// One past the largest serial of this kind in the score: a serial no note uses yet.
std::int64_t unused_serial(const Score& score, Tie tie);

// Ties the note at `at` to the note directly before it (a rest breaks ties). The pair joins the
// earlier note's tie run if it has one. Returns false when there is no note directly before.
bool tie_to_previous(Score& score, Position at, Tie tie);
// Ties every note of the list together with one new serial.
void tie_together(Score& score, const std::vector<Position>& notes, Tie tie);
// Unties the note at `at`; a neighbour left tied to nothing is untied too.
void untie_note(Score& score, Position at, Tie tie);

// The length of a note or rest (a Blank has none: quarter), and setting it.
Length length_of(const Symbol& symbol);
void set_length_of(Symbol& symbol, Length length);

// Inserts before the symbol at `at` (replacing it when it is a Blank).
void insert_symbol(Score& score, Position at, Symbol symbol);
// Ends the bar at `at`: the symbols from `at` on move into a new bar with the same clef.
void split_bar_at(Score& score, Position at);
// Removes the bar line after bar `bar`, joining the next bar into it.
void join_with_next(Score& score, std::size_t bar);
// Removes a block's symbols and the bar lines inside it.
void erase_block(Score& score, const Block& block);

// Copied symbols: bars[0] continues the bar pasted into; each further bar starts a new bar.
// A clip of whole bars (from the first symbol of a bar to the last of the same or a later one)
// pastes as bars where it goes in at a bar line.
struct Clip {
    std::vector<Bar> bars;
    bool whole_bars = false;
    bool empty() const;
    bool operator==(const Clip&) const = default;
};
Clip copy_block(const Score& score, const Block& block);
// Pastes before `at`, giving the clip's ties fresh serials so they tie only among themselves.
// Returns the position just after the pasted symbols.
Position paste_clip(Score& score, Position at, const Clip& clip);
// Pastes a clip's bars as bars of their own at a bar line: before bar `at.bar` when `at` is its
// first position, after it when `at` is its end. Returns the end of the last bar pasted.
Position paste_bars(Score& score, Position at, const Clip& clip);

// Lengths in the order a user steps through them with Left/Right: plain lengths from 32th to
// whole; a dotted length steps to the next dotted one (or the plain one where none exists).
Length shorter(Length length);
// A length as the editor's screens name it: the document spelling, but "32nd" for "32th".
std::string length_name(Length length);
// A length as a person says it: "dotted 8th", "quarter", "32nd" (never the document's
// "8th_dot").
std::string length_words(Length length);
Length longer(Length length);
// `steps` lengths longer (> 0) or shorter (< 0), stopping at whole and 32nd.
Length stepped(Length length, int steps);
// value + delta, wrapping round lowest..highest (strings and numbers).
int wrapped(int value, int delta, int lowest, int highest);
bool is_dotted(Length length);
// The dotted form of a plain length and back; nullopt when the thesis has no such length.
std::optional<Length> toggled_dot(Length length);

}  // namespace vibscore::editor
