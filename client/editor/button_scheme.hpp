#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "client/editor/buttons.hpp"
#include "client/editor/clef_book.hpp"
#include "client/editor/clef_editor.hpp"
#include "client/editor/commands.hpp"
#include "client/editor/editor_model.hpp"
#include "client/editor/entry_steps.hpp"
#include "client/editor/events.hpp"
#include "client/editor/menu.hpp"
#include "client/editor/name_entry.hpp"
#include "client/editor/shared_value.hpp"
#include "client/editor/tap_rhythm.hpp"

namespace vibscore::editor {

// What the editor asks of the world around the model after a key or button.
struct Request {
    enum class Kind {
        none,
        play,
        stop,
        save,
        save_as,
        open,
        new_score,
        quit,
        save_and_quit,
        keep_event,    // "keep as it was": give `event` back the score `name` ("" the theme's)
        hear_clef,     // play string `string` at number `number` through the clef `document`
        save_clef,     // store the clef `document` as `name` and use it for the cursor's bar
        store_clef,    // store the clef `document` as `name`: bars already use it (a tempo clef)
        assign_event,  // the score as saved plays for `event` from now on (no save, no copy)
    };
    Kind kind = Kind::none;
    std::string name;        // open: the registry name or file; save_as: the name to save under
    std::size_t bar = 0;     // play: the first bar
    bool then_quit = false;  // save_as: quit once saved
    std::string event;       // save, save_as: once saved, `event` plays it ("use for ...")
    std::string document;    // hear_clef, save_clef, store_clef: the clef as a VibClef document
    int string = 0;          // hear_clef
    int number = 0;
    bool operator==(const Request&) const = default;
};

// A name that saving under would replace something: what it is decides how the editor asks.
struct TakenName {
    enum class What {
        file,                 // a score file beside the one edited: replaced
        shipped,              // a shipped registry score: the stored one shadows it
        stored,               // a stored registry score: replaced for good
        stored_over_shipped,  // a stored score shadowing a shipped one: replaced for good
    };
    std::string name;
    What what = What::stored;
    bool operator==(const TakenName&) const = default;
};

// The six-button scheme (docs/editor.md has its table). With nothing open:
//   Up/Down       the active string          Left/Right  the cursor
//   Select        on an empty position: enter notes from there, starting with the proposed
//                 one; on a note or rest: change it, and go on from there
//   Back          the other choices (browse_choices): Up plays from the start, Down from the
//                 cursor's bar, Left goes to the first bar, Right to the end of the last one,
//                 Select opens the menu, Back turns back. Each is two presses from browsing.
// Entering (EntrySteps): each symbol in up to three steps, string, number and length; when one
// is done the next position's proposal opens (in a new bar once the last bar is full).
// Back, Back leaves.
// In a menu: Up/Down choose (wrapping), Left/Right jump between groups, Select does it,
// Back closes. Menus reopen on the last choice. While playing, any button stops.
// Save as: a name typed with the buttons (NameEntry), opening on names proposed first (the
// score's title, a free "<name>-2"): one Select takes one. Saving under a
// name that is taken (a shipped score, another stored one) asks first: another name, replace
// it, or cancel. A shipped file never changes: the stored score shadows it.
// Keyboard commands (thesis Fig. 4.3) go through command(): they drop the symbol being
// entered or close a menu first.
class ButtonScheme {
  public:
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
        playing
    };

    using Time = TapRecorder::Time;

    // `at`: when the button went down, on the clock key events are stamped with; tapping a
    // rhythm needs it (a press without it taps nothing).
    Request press(Button button, EditorModel& model, std::optional<Time> at = std::nullopt);
    // A button let go (buttons that say so: evdev keys). Only tapping listens.
    void release(Button button, Time at);
    Request command(const Command& command, EditorModel& model);
    // While a name is asked for (save as, a clef's new name), a keyboard's printable keys type it.
    bool typing_a_name() const { return mode_ == Mode::name_entry || mode_ == Mode::clef_name; }
    Request type_key(char c, EditorModel& model);

    Mode mode() const { return mode_; }
    // While entering: which step of the symbol.
    EntrySteps::Step entry_step() const { return steps_.step(); }
    // Playback started or ended (the editor is read-only in between).
    void set_playing(bool playing);
    // The scores "open..." offers.
    void set_openable(std::vector<std::string> names) { openable_ = std::move(names); }
    // The names a score is saved under already (the registry's, or the score files beside a
    // file): saving under one asks first.
    void set_taken(std::vector<TakenName> names) { taken_ = std::move(names); }
    // Where "save" stores the score; `ours` when this session made it or already replaced it
    // (saving there again asks nothing).
    // `never_saved`: a new score, whose first "save" asks what it is for.
    void set_destination(std::string name, bool ours, bool never_saved = false) {
        destination_ = std::move(name);
        destination_ours_ = ours;
        never_saved_ = never_saved;
    }
    // The events of the feedback theme in use with what each plays now: saving offers them
    // first ("use for ..."). None (vibscore-feedback out of reach) offers none.
    // `why_none`: why events cannot be chosen ("" when they can): "use for event..." says it,
    // with how to start the feedback service, instead of a list.
    void set_events(std::vector<EventScore> events, std::string why_none = "") {
        events_ = in_offer_order(std::move(events));
        why_no_events_ = std::move(why_none);
    }
    // "use for event..." (the menu's file group): the events, and Select assigns the open score
    // itself (saved first to its own name when it has unsaved changes): never a copy.
    void open_event_choice();
    // A save is done (`event`: the event it was for, or ""): a save that did not ask what the
    // score is for offers the events now (its last line, highlighted, dismisses the offer).
    void after_save(const std::string& event);
    // Saved, and `event` plays `score` now: asks "ok" or "keep as it was".
    void show_assigned(const std::string& event, const std::string& score);
    // The clefs the session could read, by id: a rhythm tapped at a clef's own pace is
    // written at its tempo; "clefs..." edits them.
    void set_clef_book(ClefBook book) { clef_book_ = std::move(book); }
    const ClefBook& clef_book() const { return *clef_book_; }
    // A clef saved: offered from now on (and never saved over: a new name each time).
    void add_clef(KnownClef clef) {
        ClefBook book = *clef_book_;
        book.put(std::move(clef));
        clef_book_ = std::move(book);
    }
    // The clef being edited, while its window is open.
    const ClefEditor* clef_editor() const;
    // The notes tapped so far while tapping.
    int taps() const { return taps_.notes(); }
    // The name being typed while saving (a score's or a clef's).
    const NameEntry& name_entry() const { return name_; }

    // What to draw for an open menu: its title, lines and the highlighted one.
    struct MenuView {
        std::string title;
        std::vector<std::string> lines;
        int highlighted = 0;
    };
    MenuView menu_view(const EditorModel& model) const;
    // One line saying what the buttons do now.
    std::string hint(const EditorModel& model) const;

    // Every part of the state, compared by value (as EditorModel's).
    bool operator==(const ButtonScheme&) const = default;

  private:
    friend struct SessionActions;  // the session's part of the action table (actions.cpp)

    Request browse(Button button, EditorModel& model);
    Request browse_choices(Button button, EditorModel& model);
    Request entry(Button button, EditorModel& model);
    Request main_menu_press(Button button, EditorModel& model);
    Request list_press(Button button, EditorModel& model);
    // An action from the menu or a key: the session's own, or the model's (actions.hpp).
    Request perform(const Command& command, EditorModel& model);
    void open_clef_menu(const EditorModel& model);
    void open_score_list();
    Request ask_quit(const EditorModel& model);
    void leave_layers(EditorModel& model);
    Request name_press(Button button);
    bool choosing(Button button, int size, Mode back_to);
    Request replace_press(Button button, const EditorModel& model);
    // Saves under `name`, or asks first when it is taken.
    Request save_under(const std::string& name, bool then_quit);
    void begin_name_entry(const EditorModel& model, bool then_quit);
    void begin_entry(EditorModel& model,
                     EditorModel::Continuing continuing = EditorModel::Continuing::no);
    Request tap(Button button, EditorModel& model, std::optional<Time> at);
    void open_use_for(bool save_as);
    void open_clef_list(EditorModel& model);
    Request clef_list_press(Button button, EditorModel& model);
    Request clef_edit_press(Button button);
    Request clef_name_press(Button button);
    Request clef_close_press(Button button);
    void begin_clef_name();
    Request use_for_press(Button button, EditorModel& model);
    Request assigned_press(Button button, EditorModel& model);
    Request end_tapping(EditorModel& model);

    Mode mode_ = Mode::browse;
    EntrySteps steps_;
    bool enter_after_list_ = false;  // the clef list of a bar begun while entering
    MenuCursor main_;
    MenuCursor list_;  // the open list menu's highlight
    int last_open_ = 0;
    Shared<std::vector<std::string>> openable_;
    Shared<std::vector<TakenName>> taken_;
    std::string destination_;
    bool destination_ours_ = true;
    NameEntry name_;
    TakenName replacing_;  // the taken name the replace menu asks about
    TapRecorder taps_;
    Shared<std::vector<EventScore>> events_;
    bool never_saved_ = false;
    std::string pending_event_;     // the event the score being saved is for
    bool pending_save_as_ = false;  // "use for" was opened by save as (else by save)
    bool assign_only_ = false;      // "use for" assigns the score as it is (use for event...)
    bool asked_for_event_ = false;  // this save asked what the score is for
    std::string why_no_events_;
    EventScore assigned_before_;  // the event as it was before the score was saved for it
    std::string assigned_score_;
    Shared<ClefBook> clef_book_;
    ClefEditor clef_editor_;
    bool then_quit_ = false;  // quit once the pending save is done
};

}  // namespace vibscore::editor
