#pragma once

#include <optional>
#include <string>
#include <vector>

#include "client/editor/button_scheme.hpp"
#include "client/editor/editor_model.hpp"

namespace vibscore::editor {

// What the screen shows besides the score.
struct ViewStatus {
    std::string name;                 // the registry name or file being edited
    std::string message;              // the editor's own news (saved, playback ended, errors)
    std::optional<Position> playing;  // the playback cursor
    // Beside each string in a clef's window, what the daemon's actuator gives there (string 1
    // first), where it declares one.
    std::vector<std::string> feel;
};

// The terminal while the editor runs: curses started in the constructor and ended in the
// destructor, on every path out. Paints the staff layout (the same one `vibscore show`
// prints), a status line and an open menu; usable from 40x12 up.
class Screen {
  public:
    Screen();
    ~Screen();
    Screen(const Screen&) = delete;
    Screen& operator=(const Screen&) = delete;

    void draw(const EditorModel& model, const ButtonScheme& scheme, const ViewStatus& status);
    // The next key (an ncurses key code), or nullopt when none is waiting.
    std::optional<int> key();

  private:
    void draw_menu(const ButtonScheme::MenuView& menu, int rows, int cols);
    int first_column_ = 0;
};

}  // namespace vibscore::editor
