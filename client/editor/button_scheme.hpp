#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "client/editor/buttons.hpp"
#include "client/editor/commands.hpp"
#include "client/editor/editor_model.hpp"
#include "client/editor/entry_steps.hpp"
#include "client/editor/menu.hpp"

namespace vibscore::editor {

// What the editor asks of the world around the model after a key or button.
struct Request {
    enum class Kind { none, play, stop, save, open, new_score, quit, save_and_quit };
    Kind kind = Kind::none;
    std::string name;     // open: the registry name or file
    std::size_t bar = 0;  // play: the first bar
    bool operator==(const Request&) const = default;
};

// The six-button scheme (docs/editor.md has its table). With nothing open:
//   Up/Down       the active string          Left/Right  the cursor
//   Select        on an empty position: enter notes from there, starting with the proposed
//                 one; on a note or rest: change it, and go on from there
//   Back          the menu
// Entering (EntrySteps): each symbol in up to three steps, string, number and length; when one
// is done the next position's proposal opens (in a new bar once the last bar is full).
// Back, Back leaves.
// In a menu: Up/Down choose (wrapping), Left/Right jump between groups, Select does it,
// Back closes. Menus reopen on the last choice. While playing, any button stops.
// Keyboard commands (thesis Fig. 4.3) go through command(): they drop the symbol being
// entered or close a menu first.
class ButtonScheme {
  public:
    enum class Mode { browse, entry, menu, clef_menu, open_menu, quit_menu, playing };

    Request press(Button button, EditorModel& model);
    Request command(const Command& command, EditorModel& model);

    Mode mode() const { return mode_; }
    // While entering: which step of the symbol.
    EntrySteps::Step entry_step() const { return steps_.step(); }
    // Playback started or ended (the editor is read-only in between).
    void set_playing(bool playing);
    // The scores "open..." offers.
    void set_openable(std::vector<std::string> names) {
        openable_ = std::make_shared<const std::vector<std::string>>(std::move(names));
    }

    // What to draw for an open menu: its title, lines and the highlighted one.
    struct MenuView {
        std::string title;
        std::vector<std::string> lines;
        int highlighted = 0;
    };
    MenuView menu_view(const EditorModel& model) const;
    // One line saying what the buttons do now.
    std::string hint(const EditorModel& model) const;

    std::string fingerprint() const;

  private:
    Request browse(Button button, EditorModel& model);
    Request entry(Button button, EditorModel& model);
    Request main_menu_press(Button button, EditorModel& model);
    Request list_press(Button button, EditorModel& model);
    Request perform(Action action, EditorModel& model);
    void open_clef_menu(const EditorModel& model);
    void leave_layers(EditorModel& model);
    void begin_entry(EditorModel& model,
                     EditorModel::Continuing continuing = EditorModel::Continuing::no);

    Mode mode_ = Mode::browse;
    EntrySteps steps_;
    bool enter_after_list_ = false;  // the clef list of a bar begun while entering
    MenuCursor main_;
    MenuCursor list_;  // the open list menu's highlight
    int last_open_ = 0;
    std::shared_ptr<const std::vector<std::string>> openable_ =
        std::make_shared<const std::vector<std::string>>();
};

}  // namespace vibscore::editor
