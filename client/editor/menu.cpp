#include "client/editor/menu.hpp"

#include <algorithm>

#include "client/editor/editor_model.hpp"
#include "client/editor/status_line.hpp"

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

std::vector<MenuRow> menu_rows(const std::vector<std::string>& lines, int width) {
    std::vector<MenuRow> rows;
    const int room = std::max(2, width);
    for (std::size_t index = 0; index < lines.size(); ++index) {
        const int line = static_cast<int>(index);
        std::string rest = lines[index];
        std::string indent;
        while (true) {
            const int columns = room - columns_of(indent);
            if (columns_of(rest) <= columns) {
                rows.push_back({indent + rest, line});
                break;
            }
            const std::size_t fits = fit(rest, columns).size();
            // Break at the last space that leaves something on this row, else within the word.
            const std::size_t space = rest.rfind(' ', fits);
            const std::size_t cut = space != std::string::npos && space > 0 ? space : fits;
            rows.push_back({indent + rest.substr(0, cut), line});
            rest.erase(0, cut);
            rest.erase(0, std::min(rest.find_first_not_of(' '), rest.size()));
            indent = " ";
            if (rest.empty()) {
                break;
            }
        }
    }
    return rows;
}

}  // namespace vibscore::editor
