#include "client/editor/button_map.hpp"

#include <libevdev/libevdev.h>

#include <charconv>
#include <stdexcept>
#include <vector>

namespace vibscore::editor {

namespace {

std::string_view trim(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
        text.remove_prefix(1);
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) {
        text.remove_suffix(1);
    }
    return text;
}

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    while (true) {
        const auto at = text.find(separator);
        parts.push_back(trim(text.substr(0, at)));
        if (at == std::string_view::npos) {
            return parts;
        }
        text.remove_prefix(at + 1);
    }
}

std::optional<int> whole_number(std::string_view text) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
        return std::nullopt;
    }
    return value;
}

unsigned key_code(std::string_view entry, std::string_view name) {
    if (const auto number = whole_number(name); number && *number >= 0 && *number <= KEY_MAX) {
        return static_cast<unsigned>(*number);
    }
    const std::string text(name);
    const int code = libevdev_event_code_from_name(EV_KEY, text.c_str());
    if (code < 0) {
        throw std::invalid_argument("button map entry \"" + std::string(entry) + "\": \"" + text +
                                    "\" is not a key (use a name like KEY_VOLUMEUP or " +
                                    "a key code)");
    }
    return static_cast<unsigned>(code);
}

}  // namespace

ButtonMap ButtonMap::phone() {
    ButtonMap map;
    map.assign(Button::up, KEY_VOLUMEUP, false);
    map.assign(Button::right, KEY_VOLUMEUP, true);
    map.assign(Button::down, KEY_VOLUMEDOWN, false);
    map.assign(Button::left, KEY_VOLUMEDOWN, true);
    map.assign(Button::select, KEY_POWER, false);
    map.assign(Button::back, KEY_POWER, true);
    return map;
}

ButtonMap ButtonMap::parse(std::string_view text) {
    ButtonMap map = phone();
    for (const auto entry : split(text, ',')) {
        if (entry.empty()) {
            continue;
        }
        if (entry == "none") {
            map.short_.clear();
            map.long_.clear();
            continue;
        }
        const auto equals = entry.find('=');
        if (equals == std::string_view::npos) {
            throw std::invalid_argument("button map entry \"" + std::string(entry) +
                                        "\": expected BUTTON=KEY, long:KEY or hold-ms=MS");
        }
        const auto name = trim(entry.substr(0, equals));
        auto value = trim(entry.substr(equals + 1));
        if (name == "hold-ms") {
            const auto ms = whole_number(value);
            if (!ms || *ms < 50 || *ms > 5000) {
                throw std::invalid_argument("button map entry \"" + std::string(entry) +
                                            "\": hold-ms is 50 to 5000");
            }
            map.hold_ms_ = *ms;
            continue;
        }
        const auto button = parse_button(name);
        if (!button) {
            throw std::invalid_argument("button map entry \"" + std::string(entry) + "\": \"" +
                                        std::string(name) +
                                        "\" is not a button (up, down, left, right, select, "
                                        "back)");
        }
        const bool held = value.starts_with("long:");
        if (held) {
            value.remove_prefix(5);
        }
        map.assign(*button, key_code(entry, trim(value)), held);
    }
    return map;
}

void ButtonMap::assign(Button button, unsigned code, bool long_press) {
    // One key per button and press length: a button given a new key leaves its old one.
    auto& map = long_press ? long_ : short_;
    std::erase_if(map, [&](const auto& pair) { return pair.second == button; });
    auto& other = long_press ? short_ : long_;
    std::erase_if(other, [&](const auto& pair) { return pair.second == button; });
    map[code] = button;
}

std::optional<Button> ButtonMap::short_press(unsigned code) const {
    const auto found = short_.find(code);
    return found == short_.end() ? std::nullopt : std::optional(found->second);
}

std::optional<Button> ButtonMap::long_press(unsigned code) const {
    const auto found = long_.find(code);
    return found == long_.end() ? std::nullopt : std::optional(found->second);
}

std::string ButtonMap::key_name(unsigned code) {
    const char* name = libevdev_event_code_get_name(EV_KEY, code);
    return name != nullptr ? name : std::to_string(code);
}

}  // namespace vibscore::editor
