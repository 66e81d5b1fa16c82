#pragma once

#include <string>
#include <vector>

#include "client/editor/commands.hpp"

namespace vibscore::editor {

class EditorModel;

struct MenuEntry {
    std::string label;
    Action action;
    int group = 0;  // Left/Right jump between groups
};

// The menu Back opens: the symbol functions first (they act on the block, or on the note or
// rest at hand), then bars, blocks, and the session. Most used first, so few presses reach them.
std::vector<MenuEntry> main_menu(const EditorModel& model);
// What a group of main_menu() holds, in a word or two: the menu's title shows it.
const char* group_name(int group);

// A highlighted line in a list that wraps around at both ends.
class MenuCursor {
  public:
    int index() const { return index_; }
    void set(int index, int size);
    void step(int delta, int size);
    // To the first entry of the next (delta > 0) or previous group, wrapping.
    void jump_group(int delta, const std::vector<MenuEntry>& entries);

  private:
    int index_ = 0;
};

}  // namespace vibscore::editor
