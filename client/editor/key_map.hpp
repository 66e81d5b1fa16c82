#pragma once

#include <optional>
#include <variant>

#include "client/editor/buttons.hpp"
#include "client/editor/commands.hpp"

namespace vibscore::editor {

// A key either is one of the six buttons or names an editing function directly.
using KeyInput = std::variant<Button, Command>;

// The keyboard (docs/editor.md): thesis Fig. 4.3 (arrows, 1-9, 0, `, Delete, c d e l g p m,
// Shift+0-9 on a US layout), Shift+arrows for blocks and strings, + and - for numbers, Ctrl
// keys for the clipboard, undo and files, Space to play; Enter and Escape/Backspace are the
// Select and Back buttons. `key` is an ncurses key code.
std::optional<KeyInput> key_input(int key);

}  // namespace vibscore::editor
