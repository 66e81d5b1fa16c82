#pragma once

#include <curses.h>

#include <algorithm>
#include <initializer_list>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/editor/editor.hpp"
#include "score/score_xml.hpp"

namespace vibscore {
// Bars and scores in failure messages, as their XML.
inline void PrintTo(const Bar& bar, std::ostream* out) {
    Score score;
    score.bars = {bar};
    *out << write_score(score);
}
inline void PrintTo(const Score& score, std::ostream* out) {
    *out << write_score(score);
}
}  // namespace vibscore

// Shared by the editor tests: editors on a fresh score, and scores written as XML.
namespace vibscore::testing {

inline const ClefDeclaration kLra{"lra", "lra-phone.clef.xml"};
inline const ClefDeclaration kErm{"erm", "erm-phone.clef.xml"};

// The six buttons by their initials, for press sequences: `using namespace testing::buttons;`.
namespace buttons {
inline constexpr auto U = editor::Button::up;
inline constexpr auto D = editor::Button::down;
inline constexpr auto L = editor::Button::left;
inline constexpr auto R = editor::Button::right;
inline constexpr auto S = editor::Button::select;
inline constexpr auto B = editor::Button::back;
}  // namespace buttons

// A new score on clef "lra", with "erm" available for bars too.
inline editor::Editor fresh_editor() {
    return {editor::EditorModel(editor::EditorModel::blank_score("t", kLra), {kLra, kErm}), {}};
}

// The bars of a score whose bars (XML) all use clef "lra".
inline std::vector<Bar> bars(const std::string& bars_xml) {
    const std::string text =
        "<VibScore><Title>t</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
        "<Clef id=\"erm\" href=\"erm-phone.clef.xml\"/>" +
        bars_xml + "</VibScore>";
    return read_score(text, "expected.xml").score.bars;
}

// Thesis Fig. 7.5, experiment 2's score task: three bars of four quarter notes, strengths 9, 3,
// 6, 3, on string 3 of clef "lra-phone", as XML.
inline std::string experiment_2_bars() {
    std::string bars;
    for (int bar = 0; bar < 3; ++bar) {
        bars += "<Bar clef=\"lra-phone\">";
        for (const int number : {9, 3, 6, 3}) {
            bars +=
                "<Note length=\"quarter\" number=\"" + std::to_string(number) + "\" string=\"3\"/>";
        }
        bars += "</Bar>";
    }
    return bars;
}

// A score (no title, no clefs declared) of bars written as XML, all on clef "lra".
inline Score score_of(const std::string& bars_xml) {
    Score score;
    score.bars = bars(bars_xml);
    return score;
}

// The end of the last bar: where entering goes on.
inline editor::Position end_of(const Score& score) {
    return {score.bars.size() - 1, score.bars.back().symbols.size()};
}

// Types keys (ncurses codes; characters as themselves) into the editor.
inline void type(editor::Editor& editor, std::initializer_list<int> keys) {
    for (const int key : keys) {
        editor.key(key);
    }
}
inline void type(editor::Editor& editor, const std::string& characters) {
    for (const char c : characters) {
        editor.key(static_cast<unsigned char>(c));
    }
}

inline void press(editor::Editor& editor, std::initializer_list<editor::Button> buttons) {
    for (const auto button : buttons) {
        editor.press(button);
    }
}

// The highlighted line of the open menu or list, or "".
inline std::string highlighted(const editor::Editor& editor) {
    const auto menu = editor.scheme.menu_view(editor.model);
    return menu.lines.empty() ? "" : menu.lines[static_cast<std::size_t>(menu.highlighted)];
}

// Opens the menu and moves down to `label`; returns the presses that took.
inline std::vector<editor::Button> to_menu_entry(editor::Editor& editor, const std::string& label) {
    std::vector<editor::Button> presses{editor::Button::back, editor::Button::select};
    editor.press(editor::Button::back);
    editor.press(editor::Button::select);
    for (int i = 0; i < 40 && highlighted(editor) != label; ++i) {
        editor.press(editor::Button::down);
        presses.push_back(editor::Button::down);
    }
    return presses;
}

// From browsing: the fewest presses that open the menu (Back, Select) and bring `label` under
// the highlight (Up, Down, and Left/Right between groups), and the Select that does it; pressed
// on `editor`, which is then where a real editor given them will be.
inline std::vector<editor::Button> menu_presses(editor::Editor& editor, const std::string& label) {
    using editor::Button;
    std::vector<Button> presses{Button::back, Button::select};
    editor.press(Button::back);
    editor.press(Button::select);
    struct Way {
        editor::Editor at;
        std::vector<Button> presses;
    };
    std::vector<Way> ways{{editor, {}}};
    for (std::size_t i = 0; i < ways.size() && i < 4096; ++i) {
        if (highlighted(ways[i].at) == label) {
            for (const Button button : ways[i].presses) {
                editor.press(button);
                presses.push_back(button);
            }
            editor.press(Button::select);
            presses.push_back(Button::select);
            return presses;
        }
        for (const Button button : {Button::up, Button::down, Button::left, Button::right}) {
            Way next{ways[i].at, ways[i].presses};
            next.at.press(button);
            next.presses.push_back(button);
            const bool seen = std::any_of(ways.begin(), ways.end(), [&](const Way& way) {
                return highlighted(way.at) == highlighted(next.at);
            });
            if (!seen) {
                ways.push_back(std::move(next));
            }
        }
    }
    throw std::runtime_error("no menu line \"" + label + "\"");
}

inline int ctrl(char letter) {
    return letter & 0x1f;
}

}  // namespace vibscore::testing
