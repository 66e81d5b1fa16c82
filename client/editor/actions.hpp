#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "client/editor/commands.hpp"

namespace vibscore::editor {

class EditorModel;
class SessionActions;
struct Request;

// The groups of the menu Back, Select opens, in their order; Left/Right jump between them.
enum class MenuGroup : std::int8_t {
    none = -1,  // not in the menu
    enter,
    hairpins,
    ties,
    symbol_bar,
    shift,
    block,
    play_go_undo,
    file,
};
inline constexpr int menu_group_count = static_cast<int>(MenuGroup::file) + 1;
// What a group holds, in a word or two: the menu's title shows it.
std::string_view group_name(MenuGroup group);

// When a menu line shows: "mark block" and "unmark block" share one place.
enum class Shown : std::uint8_t { always, unmarked, marked };

// A keyboard key (an ncurses code) and the value it gives the action (insert_note's number,
// set_length's Length); code 0 ends a record's keys.
struct KeyBinding {
    int code = 0;
    int value = 0;
};
inline constexpr std::size_t kMostKeys = 10;

// An editing function of the model (the score, cursor, block, clipboard and undo): true when
// done, false with the model's message when refused.
using ModelFunction = bool (*)(EditorModel& model, int value);
// A function of the session around the model (session_actions.hpp): a menu or list to open, or a
// request to the daemon and the files (play, save, open, quit).
using SessionFunction = Request (*)(SessionActions& session, EditorModel& model);

// One action: everything the keyboard, the menu and the dispatch know of it, in one record, as
// tmux keeps a command in one cmd_entry, so a label, a key and what they do cannot drift apart.
// Exactly one of `model` and `session` is set: which one says who does it.
struct ActionRecord {
    Action action;
    std::string_view name;
    std::array<KeyBinding, kMostKeys> keys{};
    MenuGroup group = MenuGroup::none;
    std::string_view label;  // the menu line ("" when not in the menu)
    Shown shown = Shown::always;
    ModelFunction model = nullptr;
    SessionFunction session = nullptr;

    constexpr bool in_menu() const { return group != MenuGroup::none; }
};

// Every action's record, in the order of Action.
std::span<const ActionRecord> action_records();
const ActionRecord& record_of(Action action);

// The command a keyboard key names, if any (the six buttons' keys are not commands).
std::optional<Command> command_for_key(int code);

// Each action is carried out by the model or by the session, never both or neither. Checked by
// the tests, not by a static_assert: comparing function pointers with nullptr is no constant
// expression in GCC's sanitizer builds.
bool each_action_done_by_one();

}  // namespace vibscore::editor
