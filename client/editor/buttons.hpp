#pragma once

#include <optional>
#include <string_view>

namespace vibscore::editor {

// The six buttons the whole editor can be driven with: a phone's volume keys and power key
// give three, gpio-keys or a keyboard the rest.
enum class Button { up, down, left, right, select, back };

inline constexpr Button all_buttons[] = {Button::up,    Button::down,   Button::left,
                                         Button::right, Button::select, Button::back};

std::string_view to_string(Button button);
std::optional<Button> parse_button(std::string_view name);

}  // namespace vibscore::editor
