#pragma once

#include "client/editor/button_scheme.hpp"
#include "client/editor/editor_model.hpp"
#include "client/editor/key_map.hpp"

namespace vibscore::editor {

// The editor without its screen: the model and the six-button scheme driving it. Keys and
// buttons in, score out; the terminal editor, the tests and the press planner all use this.
struct Editor {
    EditorModel model;
    ButtonScheme scheme;

    Request press(Button button) { return scheme.press(button, model); }
    bool operator==(const Editor&) const = default;
    // An ncurses key code; keys that mean nothing are ignored.
    Request key(int code) {
        const auto input = key_input(code);
        if (!input) {
            return {};
        }
        if (const auto* button = std::get_if<Button>(&*input)) {
            return press(*button);
        }
        return scheme.command(std::get<Command>(*input), model);
    }
};

}  // namespace vibscore::editor
