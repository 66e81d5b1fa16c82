#include "client/editor/menu.hpp"

#include "client/editor/editor_model.hpp"

#include <iterator>

namespace vibscore::editor {

const char* group_name(int group) {
    static const char* const names[] = {
        "hairpins", "ties", "symbol, bar", "shift", "block", "play, go to, undo", "file"};
    return group >= 0 && group < static_cast<int>(std::size(names)) ? names[group] : "";
}

std::vector<MenuEntry> main_menu(const EditorModel& model) {
    std::vector<MenuEntry> entries{
        {"decrescendo  >", Action::decrescendo, 0},
        {"crescendo  <", Action::crescendo, 0},
        {"no dynamics", Action::no_dynamics, 0},
        {"legato with previous", Action::legato, 1},
        {"portamento with previous", Action::portamento, 1},
        {"remove legato", Action::remove_legato, 1},
        {"remove portamento", Action::remove_portamento, 1},
        {"dotted / not dotted", Action::toggle_dot, 2},
        {"new bar here", Action::split_bar, 2},
        {"delete", Action::delete_symbol, 2},
        {"bar clef...", Action::choose_clef, 2},
        {"strings up", Action::strings_up, 3},
        {"strings down", Action::strings_down, 3},
        {"numbers +1", Action::numbers_up, 3},
        {"numbers -1", Action::numbers_down, 3},
        {model.marking() ? "unmark block" : "mark block",
         model.marking() ? Action::clear_block : Action::mark_block, 4},
        {"copy", Action::copy, 4},
        {"cut", Action::cut, 4},
        {"paste", Action::paste, 4},
        {"play from this bar", Action::play_or_stop, 5},
        {"play from the start", Action::play_from_start, 5},
        {"to the first bar", Action::to_first_bar, 5},
        {"to the last bar", Action::to_last_bar, 5},
        {"undo", Action::undo, 5},
        {"redo", Action::redo, 5},
        {"save", Action::save, 6},
        {"save as...", Action::save_as, 6},
        {"open...", Action::open, 6},
        {"new score", Action::new_score, 6},
        {"quit", Action::quit, 6},
    };
    return entries;
}

void MenuCursor::set(int index, int size) {
    index_ = size <= 0 ? 0 : ((index % size) + size) % size;
}

void MenuCursor::step(int delta, int size) {
    set(index_ + delta, size);
}

void MenuCursor::jump_group(int delta, const std::vector<MenuEntry>& entries) {
    const int size = static_cast<int>(entries.size());
    if (size == 0) {
        return;
    }
    // Left from anywhere in a group goes to the previous group, never to the start of its own:
    // one press per group both ways, so counting presses tells where the highlight is.
    const int group = entries[static_cast<std::size_t>(index_)].group;
    int i = index_;
    while (entries[static_cast<std::size_t>(i)].group == group) {
        i = ((i + delta) % size + size) % size;
        if (i == index_) {
            return;  // one group only
        }
    }
    if (delta < 0) {
        const int previous = entries[static_cast<std::size_t>(i)].group;
        while (entries[static_cast<std::size_t>((i - 1 + size) % size)].group == previous &&
               (i - 1 + size) % size != index_) {
            i = (i - 1 + size) % size;
        }
    }
    set(i, size);
}

}  // namespace vibscore::editor
