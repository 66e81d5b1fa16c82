#include "client/editor/name_entry.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace vibscore::editor {

namespace {

constexpr std::string_view kCharacters = "abcdefghijklmnopqrstuvwxyz0123456789-._";
constexpr std::size_t kLongestName = 64;

// Four groups of five for Up, Down, Right and Left, the characters in each for Up, Down, Right,
// Left and Select. The common groups hold the twenty letters most used in English text (Lewand's
// order: e t a o i n s h r d l c u m w f g y p) with '-', which joins the words of registry names
// (the second most common character in the shipped scores' and feedbackd's event names, after
// e); the rest, digits among them, are one press further, behind Back.
constexpr std::array<std::string_view, 4> kCommon{"etaoi", "nshrd", "lcumw", "fgyp-"};
constexpr std::array<std::string_view, 4> kRare{"bvkjx", "qz._0", "12345", "6789"};

bool starts_well(char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
}

// The group (or the character in a group) a button picks: Up, Down, Right, Left, Select.
int pick(Button button) {
    switch (button) {
        case Button::up:
            return 0;
        case Button::down:
            return 1;
        case Button::right:
            return 2;
        case Button::left:
            return 3;
        case Button::select:
            return 4;
        case Button::back:
            break;
    }
    return -1;
}

std::string groups_hint(const std::array<std::string_view, 4>& groups) {
    return "\u2191" + std::string(groups[0]) + "\u2193" + std::string(groups[1]) + "\u2192" +
           std::string(groups[2]) + "\u2190" + std::string(groups[3]);
}

std::string group_hint(std::string_view group) {
    static const char* const arrows[] = {"\u2191", "\u2193", "\u2192", "\u2190"};
    std::string hint;
    for (std::size_t i = 0; i < group.size() && i < 4; ++i) {
        hint += std::string(arrows[i]) + group[i] + " ";
    }
    if (group.size() > 4) {
        hint += "S:" + std::string(1, group[4]) + " ";
    }
    return hint + "B:back";
}

}  // namespace

bool is_registry_name(const std::string& name) {
    if (name.empty() || name.size() > kLongestName || !starts_well(name.front())) {
        return false;
    }
    return name.find_first_not_of(kCharacters) == std::string::npos;
}

void NameEntry::start(std::vector<std::string> proposals) {
    if (proposals.empty()) {
        proposals.push_back("tacton-2");
    }
    proposals_ = std::move(proposals);
    chosen_ = 0;
    name_ = proposals_.front();
    untouched_ = true;
    level_ = proposals_.size() > 1 ? Level::proposals : Level::letters;
    group_ = 0;
    refused_.clear();
}

const std::string& NameEntry::name() const {
    return level_ == Level::proposals ? proposals_[static_cast<std::size_t>(chosen_)] : name_;
}

std::string NameEntry::problem() const {
    if (!refused_.empty()) {
        return refused_;
    }
    const std::string& name = this->name();
    if (name.empty()) {
        return "a name needs a character";
    }
    if (!starts_well(name.front())) {
        return "a name starts with a letter or digit";
    }
    if (name.size() > kLongestName) {
        return "a name has at most 64 characters";
    }
    return is_registry_name(name) ? "" : "a-z 0-9 - . _ only";
}

void NameEntry::type(char c) {
    if (untouched_) {
        name_.clear();  // the proposal was shown as chosen: typing replaces it
        untouched_ = false;
    }
    if (name_.size() >= kLongestName) {
        refused_ = "a name has at most 64 characters";
        return;
    }
    name_ += c;
}

bool NameEntry::type_key(char c) {
    const char lower = c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
    const bool of_names = (lower >= 'a' && lower <= 'z') || (lower >= '0' && lower <= '9') ||
                          lower == '.' || lower == '_' || lower == '-';
    if (!of_names) {
        return false;
    }
    refused_.clear();
    level_ = Level::letters;
    type(lower);
    return true;
}

NameEntry::Outcome NameEntry::back_from_more() {
    if (proposals_.size() > 1) {
        level_ = Level::proposals;
        return Outcome::typing;
    }
    return Outcome::cancelled;
}

NameEntry::Outcome NameEntry::press(Button button) {
    refused_.clear();
    const int picked = pick(button);
    switch (level_) {
        case Level::proposals: {
            const int size = static_cast<int>(proposals_.size());
            switch (button) {
                case Button::up:
                case Button::down:
                    chosen_ = ((chosen_ + (button == Button::up ? -1 : 1)) % size + size) % size;
                    return Outcome::typing;
                case Button::select:
                    name_ = proposals_[static_cast<std::size_t>(chosen_)];
                    return Outcome::done;
                case Button::right:  // a new name
                    name_.clear();
                    untouched_ = false;
                    level_ = Level::letters;
                    return Outcome::typing;
                case Button::left:  // on from this one
                    name_ = proposals_[static_cast<std::size_t>(chosen_)];
                    untouched_ = false;
                    level_ = Level::letters;
                    return Outcome::typing;
                case Button::back:
                    return Outcome::cancelled;
            }
            return Outcome::typing;
        }
        case Level::letters:
            if (button == Button::select) {
                return problem().empty() ? Outcome::done : Outcome::typing;
            }
            if (button == Button::back) {
                level_ = Level::more;
                return Outcome::typing;
            }
            group_ = picked;
            level_ = Level::letter_group;
            return Outcome::typing;
        case Level::more:
            if (button == Button::select) {
                if (!name_.empty()) {
                    name_.pop_back();
                }
                untouched_ = false;
                level_ = Level::letters;
                return Outcome::typing;
            }
            if (button == Button::back) {
                level_ = Level::letters;
                return back_from_more();
            }
            group_ = picked;
            level_ = Level::more_group;
            return Outcome::typing;
        case Level::letter_group:
        case Level::more_group: {
            const std::string_view group = level_ == Level::letter_group
                                               ? kCommon[static_cast<std::size_t>(group_)]
                                               : kRare[static_cast<std::size_t>(group_)];
            level_ = Level::letters;
            if (picked >= 0 && static_cast<std::size_t>(picked) < group.size()) {
                type(group[static_cast<std::size_t>(picked)]);
            } else if (picked >= 0) {
                level_ = Level::more_group;  // no character there: still choosing
            }
            return Outcome::typing;
        }
    }
    return Outcome::typing;
}

std::vector<std::string> NameEntry::lines() const {
    if (level_ == Level::proposals) {
        return proposals_;
    }
    std::vector<std::string> lines{untouched_ ? "[" + name_ + "]" : name_ + "|"};
    if (const auto why = problem(); !why.empty() && (!untouched_ || !refused_.empty())) {
        lines.push_back(why);
    }
    return lines;
}

std::string NameEntry::hint() const {
    switch (level_) {
        case Level::proposals:
            return "\u2191\u2193choose S:save \u2192new \u2190edit B:cancel";
        case Level::letters:
            return groups_hint(kCommon) + " S:save B:more";
        case Level::letter_group:
            return group_hint(kCommon[static_cast<std::size_t>(group_)]);
        case Level::more:
            return groups_hint(kRare) + " S:del B:" + (proposals_.size() > 1 ? "names" : "cancel");
        case Level::more_group:
            return group_hint(kRare[static_cast<std::size_t>(group_)]);
    }
    return {};
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

std::string name_from_title(std::string_view title) {
    std::string name;
    bool gap = false;
    for (const char raw : title) {
        const char c = raw >= 'A' && raw <= 'Z' ? static_cast<char>(raw - 'A' + 'a') : raw;
        const bool kept = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_';
        if (!kept) {
            gap = !name.empty();
            continue;
        }
        if (gap) {
            name += '-';
            gap = false;
        }
        name += c;
    }
    if (name.size() > kLongestName) {
        name.resize(kLongestName);
    }
    while (!name.empty() && !starts_well(name.front())) {
        name.erase(0, 1);
    }
    return name;
}

std::vector<std::string> name_proposals(const std::string& name, const std::string& title,
                                        const std::string& event,
                                        const std::vector<std::string>& taken) {
    std::vector<std::string> proposals;
    const auto offer = [&](const std::string& proposal) {
        const bool fresh =
            is_registry_name(proposal) && proposal != name &&
            std::find(taken.begin(), taken.end(), proposal) == taken.end() &&
            std::find(proposals.begin(), proposals.end(), proposal) == proposals.end();
        if (fresh) {
            proposals.push_back(proposal);
        }
    };
    if (!event.empty()) {
        offer(free_name(event, taken));
    }
    offer(name_from_title(title));
    offer(free_name(name, taken));
    return proposals;
}

}  // namespace vibscore::editor
