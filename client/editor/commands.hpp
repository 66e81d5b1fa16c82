#pragma once

#include <string_view>

namespace vibscore::editor {

// The editing functions of thesis Fig. 4.3 and the editor's own (blocks, undo, files, playback).
// Each has one record in the action table (actions.hpp): its name, its keys, its menu line, and
// whether the model or the session around it does it. The order is the menu's order within
// each group; the table checks at compile time that it has one record per action, in this
// order.
enum class Action {
    move_left,
    move_right,
    move_up,  // to the next higher string
    move_down,
    extend_left,  // grow the block (Shift+arrow)
    extend_right,
    insert_note,  // value: the number 1..9
    insert_rest,
    insert_blank,
    set_length,  // value: a Length
    tap_rhythm,  // Select taps the notes of a rhythm (tap_rhythm.hpp)
    decrescendo,
    crescendo,
    no_dynamics,
    legato,
    portamento,
    remove_legato,
    remove_portamento,
    toggle_dot,
    split_bar,
    delete_symbol,
    choose_clef,
    edit_clefs,  // the clef editor: a clef's strings, numbers and tempo
    strings_up,
    strings_down,
    numbers_up,
    numbers_down,
    mark_block,
    clear_block,
    copy,
    cut,
    paste,
    play_or_stop,  // play from the cursor's bar
    play_from_start,
    to_first_bar,  // the start of the score
    to_last_bar,   // the end of the score, where entering goes on
    undo,
    redo,
    save,
    save_as,
    use_for_event,  // the open score plays for an event of the feedback theme (no copy)
    open,
    new_score,
    quit,
    end,  // not an action: how many there are (the table has a record for each before it)
};
inline constexpr int action_count = static_cast<int>(Action::end);

struct Command {
    Action action;
    int value = 0;
    bool operator==(const Command&) const = default;
};

// The action's name, as messages say it ("legato", "bar clef").
std::string_view to_string(Action action);

}  // namespace vibscore::editor
