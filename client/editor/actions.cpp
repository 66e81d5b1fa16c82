#include "client/editor/actions.hpp"

#include <curses.h>

#include <algorithm>
#include <iterator>
#include <unordered_map>

#include "client/editor/editor_model.hpp"
#include "client/editor/session_actions.hpp"

namespace vibscore::editor {

namespace {

constexpr int ctrl(char letter) {
    return letter & 0x1f;
}

using Keys = std::array<KeyBinding, kMostKeys>;
using enum MenuGroup;

constexpr Keys key(int code) {
    return Keys{KeyBinding{code, 0}};
}
constexpr Keys keys(int first, int second) {
    return Keys{KeyBinding{first, 0}, KeyBinding{second, 0}};
}
// '1' .. '9': the numbers 1 .. 9.
constexpr Keys digit_keys() {
    Keys found{};
    for (int n = 1; n <= 9; ++n) {
        found[static_cast<std::size_t>(n - 1)] = {'0' + n, n};
    }
    return found;
}
// Shift+1 ... Shift+9, Shift+0 on a US keyboard: the ten lengths of thesis Table 3.1 in order.
constexpr Keys shifted_digit_keys() {
    constexpr std::string_view shifted = "!@#$%^&*()";
    Keys found{};
    for (std::size_t i = 0; i < shifted.size(); ++i) {
        found[i] = {shifted[i], static_cast<int>(i)};
    }
    return found;
}

template <bool (EditorModel::*method)()>
constexpr ModelFunction call() {
    return [](EditorModel& model, int) { return (model.*method)(); };
}
template <void (EditorModel::*method)()>
constexpr ModelFunction call_void() {
    return [](EditorModel& model, int) {
        (model.*method)();
        return true;
    };
}

constexpr Keys no_keys{};

constexpr ActionRecord model(Action action, std::string_view name, Keys keys, MenuGroup group,
                             std::string_view label, ModelFunction function,
                             Shown shown = Shown::always) {
    return {action, name, keys, group, label, shown, function, nullptr};
}
constexpr ActionRecord session(Action action, std::string_view name, Keys keys, MenuGroup group,
                               std::string_view label, SessionFunction function) {
    return {action, name, keys, group, label, Shown::always, nullptr, function};
}

template <Dynamics dynamics>
bool set_dynamics(EditorModel& model, int) {
    return model.set_dynamics(dynamics);
}
template <Tie tie>
bool tie_to_previous(EditorModel& model, int) {
    return model.tie(tie);
}
template <Tie tie>
bool untie(EditorModel& model, int) {
    return model.untie(tie);
}
template <int delta>
bool extend(EditorModel& model, int) {
    model.extend(delta);
    return true;
}
template <int delta>
bool shift_strings(EditorModel& model, int) {
    return model.shift_strings(delta);
}
template <int delta>
bool shift_numbers(EditorModel& model, int) {
    return model.shift_numbers(delta);
}
bool insert_note(EditorModel& model, int number) {
    return model.insert_note(number);
}
bool set_length(EditorModel& model, int length) {
    return model.set_length_value(length);
}

// An action the session does (session_actions.hpp).
template <Request (SessionActions::*method)(EditorModel&)>
constexpr SessionFunction ask() {
    return [](SessionActions& session, EditorModel& model) { return (session.*method)(model); };
}
// Playing and a new score need nothing of the session: only a request to the world.
Request play_from_bar(SessionActions&, EditorModel& model) {
    return {Request::Kind::play, {}, model.cursor().bar};
}
Request play_from_start(SessionActions&, EditorModel&) {
    return {Request::Kind::play, {}, 0};
}
Request new_score(SessionActions&, EditorModel&) {
    return {Request::Kind::new_score};
}

// One record per action, in the order of Action (checked below); within a menu group, the
// order of the menu.
constexpr ActionRecord kActions[] = {
    model(Action::move_left, "move left", no_keys, none, "", call_void<&EditorModel::move_left>()),
    model(Action::move_right, "move right", no_keys, none, "",
          call_void<&EditorModel::move_right>()),
    model(Action::move_up, "string up", no_keys, none, "", call_void<&EditorModel::move_up>()),
    model(Action::move_down, "string down", no_keys, none, "",
          call_void<&EditorModel::move_down>()),
    model(Action::extend_left, "block left", key(KEY_SLEFT), none, "", extend<-1>),
    model(Action::extend_right, "block right", key(KEY_SRIGHT), none, "", extend<+1>),
    model(Action::insert_note, "insert note", digit_keys(), none, "", insert_note),
    model(Action::insert_rest, "insert rest", key('0'), none, "",
          call<&EditorModel::insert_rest>()),
    model(Action::insert_blank, "insert blank", key(KEY_IC), none, "",
          call<&EditorModel::insert_blank>()),
    model(Action::set_length, "set length", shifted_digit_keys(), none, "", set_length),
    session(Action::tap_rhythm, "tap a rhythm", key('t'), enter, "tap a rhythm",
            ask<&SessionActions::tap_rhythm>()),

    model(Action::decrescendo, "decrescendo", key('d'), hairpins, "decrescendo  >",
          set_dynamics<Dynamics::decrescendo>),
    model(Action::crescendo, "crescendo", key('c'), hairpins, "crescendo  <",
          set_dynamics<Dynamics::crescendo>),
    model(Action::no_dynamics, "no dynamics", key('e'), hairpins, "no dynamics",
          set_dynamics<Dynamics::none>),

    model(Action::legato, "legato", key('l'), ties, "legato with previous",
          tie_to_previous<Tie::legato>),
    model(Action::portamento, "portamento", key('p'), ties, "portamento with previous",
          tie_to_previous<Tie::portamento>),
    model(Action::remove_legato, "remove legato", key('g'), ties, "remove legato",
          untie<Tie::legato>),
    model(Action::remove_portamento, "remove portamento", key('m'), ties, "remove portamento",
          untie<Tie::portamento>),

    model(Action::toggle_dot, "dotted", key('.'), symbol_bar, "dotted / not dotted",
          call<&EditorModel::toggle_dot>()),
    model(Action::split_bar, "split bar", key('`'), symbol_bar, "new bar here",
          call<&EditorModel::split_bar>()),
    model(Action::delete_symbol, "delete", key(KEY_DC), symbol_bar, "delete",
          call<&EditorModel::delete_at_cursor>()),
    session(Action::choose_clef, "bar clef", key('k'), symbol_bar, "bar clef...",
            ask<&SessionActions::choose_clef>()),
    session(Action::edit_clefs, "edit clefs", key('K'), symbol_bar, "edit clefs...",
            ask<&SessionActions::edit_clefs>()),

    model(Action::strings_up, "strings up", key(KEY_SR), shift, "strings up", shift_strings<+1>),
    model(Action::strings_down, "strings down", key(KEY_SF), shift, "strings down",
          shift_strings<-1>),
    model(Action::numbers_up, "numbers +1", keys('+', '='), shift, "numbers +1", shift_numbers<+1>),
    model(Action::numbers_down, "numbers -1", keys('-', '_'), shift, "numbers -1",
          shift_numbers<-1>),

    model(Action::mark_block, "mark block", key('b'), block, "mark block",
          call_void<&EditorModel::mark_block>(), Shown::unmarked),
    model(Action::clear_block, "unmark block", no_keys, block, "unmark block",
          call_void<&EditorModel::clear_block>(), Shown::marked),
    model(Action::copy, "copy", key(ctrl('C')), block, "copy", call<&EditorModel::copy>()),
    model(Action::cut, "cut", key(ctrl('X')), block, "cut", call<&EditorModel::cut>()),
    model(Action::paste, "paste", key(ctrl('V')), block, "paste", call<&EditorModel::paste>()),

    session(Action::play_or_stop, "play", key(' '), play_go_undo, "play from this bar",
            play_from_bar),
    session(Action::play_from_start, "play from the start", no_keys, play_go_undo,
            "play from the start", play_from_start),
    model(Action::to_first_bar, "to the first bar", key(KEY_HOME), play_go_undo, "to the first bar",
          call_void<&EditorModel::to_first_bar>()),
    model(Action::to_last_bar, "to the last bar", key(KEY_END), play_go_undo, "to the last bar",
          call_void<&EditorModel::to_last_bar>()),
    model(Action::undo, "undo", key(ctrl('Z')), play_go_undo, "undo", call<&EditorModel::undo>()),
    model(Action::redo, "redo", key(ctrl('Y')), play_go_undo, "redo", call<&EditorModel::redo>()),

    session(Action::save, "save", key(ctrl('S')), file, "save", ask<&SessionActions::save>()),
    session(Action::save_as, "save as", no_keys, file, "save as...",
            ask<&SessionActions::save_as>()),
    session(Action::use_for_event, "use for event", key('u'), file, "use for event...",
            ask<&SessionActions::use_for_event>()),
    session(Action::open, "open", key(ctrl('O')), file, "open...", ask<&SessionActions::open>()),
    session(Action::new_score, "new", key(ctrl('N')), file, "new score", new_score),
    session(Action::quit, "quit", keys(ctrl('Q'), 'q'), file, "quit", ask<&SessionActions::quit>()),
};

// The table is checked when it compiles: a record for every action, in order; each done by the
// model or by the session, never both or neither; a menu line exactly for the actions in a
// group, the groups in menu order; no key given to two actions.
constexpr bool one_record_per_action_in_order() {
    if (std::size(kActions) != static_cast<std::size_t>(action_count)) {
        return false;
    }
    for (std::size_t i = 0; i < std::size(kActions); ++i) {
        if (kActions[i].action != static_cast<Action>(i)) {
            return false;
        }
    }
    return true;
}
static_assert(one_record_per_action_in_order(), "one record per Action, in the order of Action");

constexpr bool each_done_by_one() {
    for (const auto& record : kActions) {
        if ((record.model == nullptr) == (record.session == nullptr)) {
            return false;
        }
    }
    return true;
}

constexpr bool menu_lines_where_groups_are() {
    int last_group = -1;
    for (const auto& record : kActions) {
        if (record.in_menu() == record.label.empty()) {
            return false;
        }
        const int group = static_cast<int>(record.group);
        if (record.in_menu()) {
            if (group < last_group) {
                return false;  // the menu's groups come in table order
            }
            last_group = group;
        }
    }
    return true;
}
static_assert(menu_lines_where_groups_are(),
              "a label exactly for the actions in the menu, grouped in menu order");

constexpr bool no_key_twice() {
    for (std::size_t i = 0; i < std::size(kActions); ++i) {
        for (const auto& a : kActions[i].keys) {
            if (a.code == 0) {
                break;
            }
            for (std::size_t j = i; j < std::size(kActions); ++j) {
                for (const auto& b : kActions[j].keys) {
                    if (b.code == 0) {
                        break;
                    }
                    if (a.code == b.code && &a != &b) {
                        return false;
                    }
                }
            }
        }
    }
    return true;
}
static_assert(no_key_twice(), "no key names two actions");

}  // namespace

std::string_view group_name(MenuGroup group) {
    switch (group) {
        case MenuGroup::none:
            return "";
        case MenuGroup::enter:
            return "enter";
        case MenuGroup::hairpins:
            return "hairpins";
        case MenuGroup::ties:
            return "ties";
        case MenuGroup::symbol_bar:
            return "symbol, bar";
        case MenuGroup::shift:
            return "shift";
        case MenuGroup::block:
            return "block";
        case MenuGroup::play_go_undo:
            return "play, go to, undo";
        case MenuGroup::file:
            return "file";
    }
    return "";
}

std::span<const ActionRecord> action_records() {
    return kActions;
}

const ActionRecord& record_of(Action action) {
    return kActions[static_cast<std::size_t>(action)];
}

std::string_view to_string(Action action) {
    const auto index = static_cast<std::size_t>(action);
    return index < std::size(kActions) ? kActions[index].name : "?";
}

std::optional<Command> command_for_key(int code) {
    static const auto by_key = [] {
        std::unordered_map<int, Command> found;
        for (const auto& record : kActions) {
            for (const auto& binding : record.keys) {
                if (binding.code == 0) {
                    break;
                }
                found.emplace(binding.code, Command{record.action, binding.value});
            }
        }
        return found;
    }();
    if (const auto found = by_key.find(code); found != by_key.end()) {
        return found->second;
    }
    return std::nullopt;
}

bool each_action_done_by_one() {
    return each_done_by_one();
}

// A keyboard command on the model: here, beside the table it looks the action up in, so the
// model's own file needs nothing of the table (the table stands above the model it calls).
bool EditorModel::apply(const Command& command) {
    if (static_cast<int>(command.action) < 0 || static_cast<int>(command.action) >= action_count) {
        return refuse("no such editing function");
    }
    const auto& record = record_of(command.action);
    if (record.model == nullptr) {
        return refuse(std::string(record.name) + " is not an editing function");
    }
    return record.model(*this, command.value);
}

}  // namespace vibscore::editor
