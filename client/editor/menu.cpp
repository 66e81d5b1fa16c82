#include "client/editor/menu.hpp"

#include "client/editor/editor_model.hpp"

namespace vibscore::editor {

std::vector<MenuEntry> main_menu(const EditorModel& model) {
    std::vector<MenuEntry> entries;
    for (const auto& record : action_records()) {
        const bool shown =
            record.shown == Shown::always || (record.shown == Shown::marked) == model.marking();
        if (record.in_menu() && shown) {
            entries.push_back({std::string(record.label), record.action, record.group});
        }
    }
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
    const MenuGroup group = entries[static_cast<std::size_t>(index_)].group;
    int i = index_;
    while (entries[static_cast<std::size_t>(i)].group == group) {
        i = ((i + delta) % size + size) % size;
        if (i == index_) {
            return;  // one group only
        }
    }
    if (delta < 0) {
        const MenuGroup previous = entries[static_cast<std::size_t>(i)].group;
        while (entries[static_cast<std::size_t>((i - 1 + size) % size)].group == previous &&
               (i - 1 + size) % size != index_) {
            i = (i - 1 + size) % size;
        }
    }
    set(i, size);
}

}  // namespace vibscore::editor
