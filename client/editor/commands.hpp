#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace vibscore::editor {

// The editing functions of thesis Fig. 4.3 and the editor's own (blocks, undo, files, playback).
// A keyboard key names one; the six-button scheme reaches each through its menus.
enum class Action {
    move_left,
    move_right,
    move_up,  // to the next higher string
    move_down,
    to_first_bar,  // the start of the score
    to_last_bar,   // the end of the score, where entering goes on
    extend_left,   // grow the block (Shift+arrow)
    extend_right,
    insert_note,  // value: the number 1..9
    insert_rest,
    insert_blank,
    split_bar,
    delete_symbol,
    crescendo,
    decrescendo,
    no_dynamics,
    legato,
    remove_legato,
    portamento,
    remove_portamento,
    set_length,  // value: a Length
    toggle_dot,
    strings_up,
    strings_down,
    numbers_up,
    numbers_down,
    mark_block,
    clear_block,
    copy,
    cut,
    paste,
    undo,
    redo,
    // Handled by the editor around the model: menus, the daemon and files.
    choose_clef,
    play_or_stop,
    play_from_start,
    save,
    save_as,
    open,
    new_score,
    quit,
};

struct Command {
    Action action;
    int value = 0;
    bool operator==(const Command&) const = default;
};

std::string_view to_string(Action action);

}  // namespace vibscore::editor
