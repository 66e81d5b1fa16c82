#include "client/editor/commands.hpp"

namespace vibscore::editor {

std::string_view to_string(Action action) {
    switch (action) {
        case Action::move_left:
            return "move left";
        case Action::move_right:
            return "move right";
        case Action::move_up:
            return "string up";
        case Action::move_down:
            return "string down";
        case Action::to_first_bar:
            return "to the first bar";
        case Action::to_last_bar:
            return "to the last bar";
        case Action::extend_left:
            return "block left";
        case Action::extend_right:
            return "block right";
        case Action::insert_note:
            return "insert note";
        case Action::insert_rest:
            return "insert rest";
        case Action::insert_blank:
            return "insert blank";
        case Action::split_bar:
            return "split bar";
        case Action::delete_symbol:
            return "delete";
        case Action::crescendo:
            return "crescendo";
        case Action::decrescendo:
            return "decrescendo";
        case Action::no_dynamics:
            return "no dynamics";
        case Action::legato:
            return "legato";
        case Action::remove_legato:
            return "remove legato";
        case Action::portamento:
            return "portamento";
        case Action::remove_portamento:
            return "remove portamento";
        case Action::set_length:
            return "set length";
        case Action::toggle_dot:
            return "dotted";
        case Action::strings_up:
            return "strings up";
        case Action::strings_down:
            return "strings down";
        case Action::numbers_up:
            return "numbers +1";
        case Action::numbers_down:
            return "numbers -1";
        case Action::mark_block:
            return "mark block";
        case Action::clear_block:
            return "unmark block";
        case Action::copy:
            return "copy";
        case Action::cut:
            return "cut";
        case Action::paste:
            return "paste";
        case Action::undo:
            return "undo";
        case Action::redo:
            return "redo";
        case Action::choose_clef:
            return "bar clef";
        case Action::play_or_stop:
            return "play";
        case Action::play_from_start:
            return "play from the start";
        case Action::save:
            return "save";
        case Action::save_as:
            return "save as";
        case Action::open:
            return "open";
        case Action::new_score:
            return "new";
        case Action::quit:
            return "quit";
    }
    return "?";
}

}  // namespace vibscore::editor
