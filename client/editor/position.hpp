#pragma once

#include <compare>
#include <cstddef>

namespace vibscore::editor {

// A place in a score where the editing cursor can stand: on symbol number `symbol` of bar `bar`
// (the index the bus reports as `symbol`), or, when `symbol` equals the bar's symbol count, on
// the empty position at the end of that bar.
// Positions order as the symbols are played.
struct Position {
    std::size_t bar = 0;
    std::size_t symbol = 0;
    auto operator<=>(const Position&) const = default;
};

// A block of symbols: from `first` up to, not including, `end` (both positions).
struct Block {
    Position first;
    Position end;
    bool operator==(const Block&) const = default;
};

}  // namespace vibscore::editor
