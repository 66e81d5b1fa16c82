#include "client/editor/name_entry.hpp"

#include <algorithm>
#include <string_view>
#include <utility>

namespace vibscore::editor {

namespace {

// The characters a registry name may hold, in the order Up steps through them.
constexpr std::string_view kCharacters = "abcdefghijklmnopqrstuvwxyz0123456789-._";
constexpr std::size_t kLongestName = 64;

char stepped_character(char c, int delta) {
    const auto at = kCharacters.find(c);
    const auto size = static_cast<int>(kCharacters.size());
    const int from = at == std::string_view::npos ? 0 : static_cast<int>(at);
    return kCharacters[static_cast<std::size_t>(((from + delta) % size + size) % size)];
}

bool starts_well(char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
}

}  // namespace

bool is_registry_name(const std::string& name) {
    if (name.empty() || name.size() > kLongestName || !starts_well(name.front())) {
        return false;
    }
    return name.find_first_not_of(kCharacters) == std::string::npos;
}

void NameEntry::start(std::string name) {
    name_ = std::move(name);
    if (name_.empty()) {
        name_ = "a";
    }
    cursor_ = name_.size() - 1;
    more_ = false;
}

std::string NameEntry::problem() const {
    if (name_.empty()) {
        return "a name needs a character";
    }
    if (!starts_well(name_.front())) {
        return "a name starts with a letter or digit";
    }
    if (name_.size() > kLongestName) {
        return "a name has at most 64 characters";
    }
    return is_registry_name(name_) ? "" : "a-z 0-9 - . _ only";
}

NameEntry::Outcome NameEntry::press(Button button) {
    if (more_) {
        more_ = false;
        switch (button) {
            case Button::down:
                if (name_.size() > 1) {
                    name_.erase(cursor_, 1);
                    cursor_ = std::min(cursor_, name_.size() - 1);
                }
                return Outcome::typing;
            case Button::up:
                name_.insert(cursor_, 1, name_[cursor_]);
                return Outcome::typing;
            case Button::back:
                return Outcome::cancelled;
            default:
                return Outcome::typing;
        }
    }
    switch (button) {
        case Button::up:
        case Button::down:
            name_[cursor_] = stepped_character(name_[cursor_], button == Button::up ? +1 : -1);
            return Outcome::typing;
        case Button::left:
            cursor_ = cursor_ == 0 ? 0 : cursor_ - 1;
            return Outcome::typing;
        case Button::right:
            if (cursor_ + 1 == name_.size() && name_.size() < kLongestName) {
                name_ += 'a';
            }
            cursor_ = std::min(cursor_ + 1, name_.size() - 1);
            return Outcome::typing;
        case Button::back:
            more_ = true;
            return Outcome::typing;
        case Button::select:
            return problem().empty() ? Outcome::done : Outcome::typing;
    }
    return Outcome::typing;
}

std::string NameEntry::shown() const {
    return name_.substr(0, cursor_) + "[" + name_.substr(cursor_, 1) + "]" +
           name_.substr(cursor_ + 1);
}

std::string free_name(const std::string& name, const std::vector<std::string>& taken) {
    // "ringtone-2" is a second ringtone: its successor is "ringtone-3", not "ringtone-2-2".
    std::string base = name;
    const auto dash = base.find_last_of('-');
    if (dash != std::string::npos && dash + 1 < base.size() &&
        base.find_first_not_of("0123456789", dash + 1) == std::string::npos) {
        base.resize(dash);
    }
    if (!is_registry_name(base)) {
        base = "tacton";
    }
    for (int n = 2;; ++n) {
        const std::string suffix = "-" + std::to_string(n);
        const std::string candidate = base.substr(0, kLongestName - suffix.size()) + suffix;
        if (std::find(taken.begin(), taken.end(), candidate) == taken.end()) {
            return candidate;
        }
    }
}

std::string NameEntry::hint() const {
    if (more_) {
        return "\u2193delete \u2191insert S:type B:cancel";
    }
    const char c = name_[cursor_];
    return "\u2191" + std::string(1, stepped_character(c, +1)) + " \u2193" +
           std::string(1, stepped_character(c, -1)) + " \u2190\u2192move S:save B:more";
}

}  // namespace vibscore::editor
