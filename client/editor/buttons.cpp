#include "client/editor/buttons.hpp"

namespace vibscore::editor {

std::string_view to_string(Button button) {
    switch (button) {
        case Button::up:
            return "up";
        case Button::down:
            return "down";
        case Button::left:
            return "left";
        case Button::right:
            return "right";
        case Button::select:
            return "select";
        case Button::back:
            return "back";
    }
    return "?";
}

std::optional<Button> parse_button(std::string_view name) {
    for (const Button button : all_buttons) {
        if (to_string(button) == name) {
            return button;
        }
    }
    return std::nullopt;
}

}  // namespace vibscore::editor
