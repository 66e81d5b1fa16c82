#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "score/length.hpp"

namespace vibscore {

enum class Dynamics { none, crescendo, decrescendo };

// A vibrotactile note: pitch by string, strength by the number in its head (thesis §2.2).
// string and number are 1-based, as written in the document.
struct Note {
    Length length = Length::quarter;
    int number = 1;
    int string = 1;
    Dynamics dynamics = Dynamics::none;
    // Consecutive notes sharing the same non-zero serial are tied; 0 means not tied.
    std::int64_t legato = 0;
    std::int64_t portamento = 0;

    bool operator==(const Note&) const = default;
};

struct Rest {
    Length length = Length::quarter;
    bool operator==(const Rest&) const = default;
};

// White space kept for the editor's layout; it takes no time.
struct Blank {
    bool operator==(const Blank&) const = default;
};

using Symbol = std::variant<Note, Rest, Blank>;

struct Bar {
    std::string clef;  // a ClefDeclaration id
    std::vector<Symbol> symbols;
    bool operator==(const Bar&) const = default;
};

struct ClefDeclaration {
    std::string id;
    std::string href;  // relative to the score document
    bool operator==(const ClefDeclaration&) const = default;
};

struct Score {
    std::string version = "1.0";
    std::string title;
    std::vector<ClefDeclaration> clefs;
    std::vector<Bar> bars;

    bool operator==(const Score&) const = default;

    const ClefDeclaration* find_clef(std::string_view id) const;
    // Sum of the lengths of a bar's notes and rests, in quarter notes.
    static double beat_count(const Bar& bar);
};

std::string_view to_string(Dynamics dynamics);

}  // namespace vibscore
