#pragma once

namespace vibscore::editor {

// What the six buttons do depends on the mode the editor is in. Each mode has one record in the
// mode table (mode_table.cpp): what each button does, the status line's text and what is drawn,
// so a button's meaning, its hint and its menu cannot drift apart. The order is the table's;
// it checks at compile time that it has one record per mode, in this order.
enum class Mode {
    browse,
    browse_choices,  // Back from browsing: play, go to the first or last bar, the menu
    entry,
    menu,
    clef_menu,
    open_menu,
    quit_menu,
    name_entry,    // save as: typing the name
    replace_menu,  // the name is taken: another name, replace it, cancel
    tapping,       // a rhythm tapped on Select (tap_rhythm.hpp)
    use_for,       // saving: which event the score is for, or none
    assigned,      // saved for an event: ok, or keep the event as it was
    no_events,     // "use for event...": why there are none (the service not running)
    clef_list,     // "edit clefs...": which clef
    clef_edit,     // a clef's window (clef_editor.hpp)
    clef_name,     // saving the clef: its new name
    clef_close,    // closing an edited clef: save as, drop the changes, cancel
    playing,
    end,  // not a mode: how many there are (the table has a record for each before it)
};
inline constexpr int mode_count = static_cast<int>(Mode::end);

}  // namespace vibscore::editor
