#include "client/editor/key_map.hpp"

#include <curses.h>

#include <string_view>

#include "score/length.hpp"

namespace vibscore::editor {

namespace {

constexpr int ctrl(char letter) {
    return letter & 0x1f;
}

// Shift+1 ... Shift+9, Shift+0 on a US keyboard: the ten lengths of Table 3.1 in order.
constexpr std::string_view kShiftedDigits = "!@#$%^&*()";

}  // namespace

std::optional<KeyInput> key_input(int key) {
    switch (key) {
        case KEY_UP:
            return Button::up;
        case KEY_DOWN:
            return Button::down;
        case KEY_LEFT:
            return Button::left;
        case KEY_RIGHT:
            return Button::right;
        case '\n':
        case '\r':
        case KEY_ENTER:
            return Button::select;
        case 27:  // Escape
        case KEY_BACKSPACE:
        case 127:
        case ctrl('H'):
            return Button::back;
        case '0':
            return Command{Action::insert_rest};
        case '`':
            return Command{Action::split_bar};
        case KEY_DC:
            return Command{Action::delete_symbol};
        case KEY_IC:
            return Command{Action::insert_blank};
        case 'c':
            return Command{Action::crescendo};
        case 'd':
            return Command{Action::decrescendo};
        case 'e':
            return Command{Action::no_dynamics};
        case 'l':
            return Command{Action::legato};
        case 'g':
            return Command{Action::remove_legato};
        case 'p':
            return Command{Action::portamento};
        case 'm':
            return Command{Action::remove_portamento};
        case '.':
            return Command{Action::toggle_dot};
        case KEY_HOME:
            return Command{Action::to_first_bar};
        case KEY_END:
            return Command{Action::to_last_bar};
        case KEY_SLEFT:
            return Command{Action::extend_left};
        case KEY_SRIGHT:
            return Command{Action::extend_right};
        case KEY_SR:  // Shift+Up
            return Command{Action::strings_up};
        case KEY_SF:  // Shift+Down
            return Command{Action::strings_down};
        case '+':
        case '=':
            return Command{Action::numbers_up};
        case '-':
        case '_':
            return Command{Action::numbers_down};
        case 'b':
            return Command{Action::mark_block};
        case ctrl('C'):
            return Command{Action::copy};
        case ctrl('X'):
            return Command{Action::cut};
        case ctrl('V'):
            return Command{Action::paste};
        case ctrl('Z'):
            return Command{Action::undo};
        case ctrl('Y'):
            return Command{Action::redo};
        case 'k':
            return Command{Action::choose_clef};
        case ' ':
            return Command{Action::play_or_stop};
        case ctrl('S'):
            return Command{Action::save};
        case ctrl('O'):
            return Command{Action::open};
        case ctrl('N'):
            return Command{Action::new_score};
        case ctrl('Q'):
        case 'q':
            return Command{Action::quit};
        default:
            break;
    }
    if (key >= '1' && key <= '9') {
        return Command{Action::insert_note, key - '0'};
    }
    if (key > 0 && key < 128) {
        if (const auto at = kShiftedDigits.find(static_cast<char>(key));
            at != std::string_view::npos) {
            return Command{Action::set_length, static_cast<int>(at)};
        }
    }
    return std::nullopt;
}

}  // namespace vibscore::editor
