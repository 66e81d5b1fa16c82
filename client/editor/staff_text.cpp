#include "client/editor/staff_text.hpp"

#include <string>

namespace vibscore::client {

namespace {

using editor::Cell;
using editor::Ink;

// The SGR parameters for a cell: its ink's colour, then the marks laid over it.
std::string sgr(const Cell& cell) {
    std::string codes;
    switch (cell.ink) {
        case Ink::blank:
            break;
        case Ink::line:
            codes = "90";
            break;
        case Ink::head:
        case Ink::rest:
            codes = "1";
            break;
        case Ink::sustain:
            codes = "37";
            break;
        case Ink::dynamics:
            codes = "33";
            break;
        case Ink::tie:
            codes = "32";
            break;
        case Ink::length:
            codes = "2";
            break;
        case Ink::clef_fewer:
            codes = "30;46";
            break;
        case Ink::clef_exact:
            codes = "30;47";
            break;
        case Ink::clef_more:
            codes = "30;45";
            break;
        case Ink::playback:
            codes = "31";
            break;
        case Ink::mark:
            codes = "1";
            break;
    }
    const auto add = [&](const char* code) {
        codes += codes.empty() ? "" : ";";
        codes += code;
    };
    if (cell.overlay & editor::overlay_cursor_column) {
        add("44");
    }
    if (cell.overlay & editor::overlay_selected) {
        add("43");
    }
    if (cell.overlay & editor::overlay_playing) {
        add("41");
    }
    if (cell.overlay & editor::overlay_cursor) {
        add("7");
    }
    return codes;
}

}  // namespace

std::string staff_row_text(const editor::StaffLayout& layout, int row, int begin, int end,
                           bool colour) {
    std::string text;
    std::string current;
    const auto& cells = layout.rows.at(static_cast<std::size_t>(row));
    for (int x = begin; x < end && x < layout.width; ++x) {
        const Cell& cell = cells[static_cast<std::size_t>(x)];
        if (colour) {
            const std::string wanted = sgr(cell);
            if (wanted != current) {
                text += "\x1b[0m";
                if (!wanted.empty()) {
                    text += "\x1b[" + wanted + "m";
                }
                current = wanted;
            }
        }
        text += cell.glyph;
    }
    if (colour && !current.empty()) {
        text += "\x1b[0m";
    }
    // Trailing blanks carry nothing; plain text without them compares and pipes better.
    if (!colour) {
        text.erase(text.find_last_not_of(' ') + 1);
    }
    return text;
}

void print_staff(std::ostream& out, const Score& score, const StaffTextOptions& options) {
    const auto layout = editor::layout_staff(score);
    out << (score.title.empty() ? std::string("(untitled)") : score.title) << "\n";
    for (const auto& [begin, end] : editor::systems(layout, options.width)) {
        out << "\n";
        // The playback row stays empty outside the editor.
        for (int row = 0; row < editor::row_playback; ++row) {
            out << staff_row_text(layout, row, begin, end, options.colour) << "\n";
        }
    }
}

}  // namespace vibscore::client
