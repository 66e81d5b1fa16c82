#include "client/editor/key_map.hpp"

#include <curses.h>

#include "client/editor/actions.hpp"

namespace vibscore::editor {

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
        case 'H' & 0x1f:  // Ctrl+H
            return Button::back;
        default:
            break;
    }
    // Every other key is in the action table, with the action it names.
    if (const auto command = command_for_key(key)) {
        return *command;
    }
    return std::nullopt;
}

}  // namespace vibscore::editor
