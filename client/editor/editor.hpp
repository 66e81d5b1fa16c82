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
    // With the time it went down, for tapping a rhythm; a release likewise.
    Request press_at(Button button, ButtonScheme::Time at) {
        return scheme.press(button, model, at);
    }
    void release_at(Button button, ButtonScheme::Time at) { scheme.release(button, at); }
    bool operator==(const Editor&) const = default;
    // An ncurses key code; keys that mean nothing are ignored.
    Request key(int code, std::optional<ButtonScheme::Time> at = std::nullopt) {
        if (scheme.typing_a_name() && code > ' ' && code < 127) {
            return scheme.type_key(static_cast<char>(code), model);
        }
        const auto input = key_input(code);
        if (!input) {
            return {};
        }
        if (const auto* button = std::get_if<Button>(&*input)) {
            return scheme.press(*button, model, at);
        }
        return scheme.command(std::get<Command>(*input), model);
    }
};

}  // namespace vibscore::editor
