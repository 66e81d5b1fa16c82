#pragma once

#include <string>
#include <vector>

#include "client/editor/actions.hpp"
#include "client/editor/commands.hpp"

namespace vibscore::editor {

class EditorModel;

struct MenuEntry {
    std::string label;
    Action action;
    MenuGroup group = MenuGroup::none;  // Left/Right jump between groups
};

// The menu Back, Select opens, from the action table (actions.hpp): the symbol functions first
// (they act on the block, or on the note or rest at hand), then bars, blocks, and the session.
// Most used first, so few presses reach them.
std::vector<MenuEntry> main_menu(const EditorModel& model);

// A menu line as drawn: lines longer than the menu is wide are wrapped at spaces (a word
// longer than the width is broken), their continuations indented one column, so an event's
// name and what it plays show whole at 40 columns. `line`: the menu line a row belongs to.
struct MenuRow {
    std::string text;
    int line = 0;
    bool operator==(const MenuRow&) const = default;
};
std::vector<MenuRow> menu_rows(const std::vector<std::string>& lines, int width);

// A highlighted line in a list that wraps around at both ends.
class MenuCursor {
  public:
    int index() const { return index_; }
    void set(int index, int size);
    void step(int delta, int size);
    // To the first entry of the next (delta > 0) or previous group, wrapping.
    void jump_group(int delta, const std::vector<MenuEntry>& entries);

    bool operator==(const MenuCursor&) const = default;

  private:
    int index_ = 0;
};

}  // namespace vibscore::editor
