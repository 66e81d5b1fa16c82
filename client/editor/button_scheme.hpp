#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
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
#include "client/editor/modes.hpp"
#include "client/editor/name_entry.hpp"
#include "client/editor/request.hpp"
#include "client/editor/session_actions.hpp"
#include "client/editor/shared_value.hpp"
#include "client/editor/status_line.hpp"
#include "client/editor/tap_rhythm.hpp"

namespace vibscore::editor {

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
class ButtonScheme : public SessionActions {
  public:
    // The modes (modes.hpp), each with one record in the mode table (mode_table.cpp).
    using Mode = editor::Mode;

    using Time = TapRecorder::Time;

    // `at`: when the button went down, on the clock key events are stamped with; tapping a
    // rhythm needs it (a press without it taps nothing).
    Request press(Button button, EditorModel& model, std::optional<Time> at = std::nullopt);
    // A button let go (buttons that say so: evdev keys). Only tapping listens.
    void release(Button button, Time at);
    Request command(const Command& command, EditorModel& model);
    // While a name is asked for (save as, a clef's new name), a keyboard's printable keys type it.
    bool typing_a_name() const;
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
    // One line saying what the buttons do now (the mode's status text).
    std::string hint(const EditorModel& model) const;

    // Every part of the state, compared by value (as EditorModel's).
    bool operator==(const ButtonScheme&) const = default;

    // --- the mode table -------------------------------------------------------------------
    // A step of the scheme's own that a button takes in a mode (a list's highlight, a layer's
    // own buttons, ending a rhythm). `at`: when the button went down, if known.
    using Step = Request (ButtonScheme::*)(Button button, EditorModel& model,
                                           std::optional<Time> at);
    // What one button does in one mode: first it goes to the mode `then` (if any), then it
    // carries out `action` from the action table (what the menu and the keyboard do for it) or
    // takes `step`. A button that does none of these is unused, and its `does` is "".
    struct ButtonUse {
        std::string_view does;  // in words, as the hints say it ("string up", "choose")
        std::optional<Mode> then;
        Action action = Action::end;  // Action::end: no action
        Step step = nullptr;

        constexpr bool used() const {
            return then.has_value() || action != Action::end || step != nullptr;
        }
    };
    // What a keyboard command (an action's key) does in a mode.
    enum class Keyboard {
        leave,      // the mode is left (a symbol being entered dropped), then the action done
        stop,       // playback stops; nothing else
        typing,     // a name is being typed: the key is refused, with what names take
        clef_open,  // a clef is open: the key is refused, with how to close it
    };
    // One mode: what each of the six buttons does, what the status line says and what is
    // drawn, in one record, as the action table keeps an action's key, menu line and function
    // in one (tmux drives every mode's keys from such records).
    struct ModeRecord {
        Mode mode;
        std::string_view name;
        std::array<ButtonUse, std::size(all_buttons)> buttons;  // in the order of Button
        // The status line's text: `hint` when it never changes, else `live_hint`'s.
        std::string_view hint;
        std::string (ButtonScheme::*live_hint)(const EditorModel& model) const = nullptr;
        // What is drawn over the staff (nullptr: nothing).
        MenuView (ButtonScheme::*menu)(const EditorModel& model) const = nullptr;
        // How many lines Up and Down move through, in a list (nullptr: no list).
        int (ButtonScheme::*choices)(const EditorModel& model) const = nullptr;
        Keyboard keyboard = Keyboard::leave;
        bool news_shown = false;   // what the last action did shows on the status line
        bool clef_window = false;  // a clef's window is open (clef_editor())
    };
    // Every mode's record, in the order of Mode (checked when the table compiles).
    static std::span<const ModeRecord> modes();
    static const ModeRecord& mode_record(Mode mode);

  private:
    const ModeRecord& record() const { return mode_record(mode_); }

    // The session's part of the action table (session_actions.hpp).
    Request choose_clef(EditorModel& model) override;
    Request edit_clefs(EditorModel& model) override;
    Request save(EditorModel& model) override;
    Request save_as(EditorModel& model) override;
    Request use_for_event(EditorModel& model) override;
    Request open(EditorModel& model) override;
    Request tap_rhythm(EditorModel& model) override;
    Request quit(EditorModel& model) override;

    // Steps the mode table gives buttons (Step).
    Request stop(Button, EditorModel&, std::optional<Time>);
    Request begin_entry_step(Button, EditorModel& model, std::optional<Time>);
    Request open_choices(Button, EditorModel& model, std::optional<Time>);
    Request entry(Button button, EditorModel& model, std::optional<Time>);
    Request menu_step(Button button, EditorModel& model, std::optional<Time>);
    Request menu_group(Button button, EditorModel& model, std::optional<Time>);
    Request menu_choose(Button, EditorModel& model, std::optional<Time>);
    Request list_step(Button button, EditorModel& model, std::optional<Time>);
    Request list_back_to_menu(Button, EditorModel& model, std::optional<Time>);
    Request list_back_to_browse(Button, EditorModel& model, std::optional<Time>);
    Request choose_bar_clef(Button, EditorModel& model, std::optional<Time>);
    Request choose_score(Button, EditorModel& model, std::optional<Time>);
    Request choose_quit(Button, EditorModel& model, std::optional<Time>);
    Request name_press(Button button, EditorModel&, std::optional<Time>);
    Request replace_choose(Button, EditorModel& model, std::optional<Time>);
    Request tap_note(Button, EditorModel&, std::optional<Time> at);
    Request tap_rest(Button, EditorModel&, std::optional<Time> at);
    Request finish_tapping(Button, EditorModel& model, std::optional<Time> at);
    Request drop_tapping(Button, EditorModel& model, std::optional<Time>);
    Request use_for_choose(Button, EditorModel& model, std::optional<Time>);
    Request assigned_choose(Button, EditorModel& model, std::optional<Time>);
    Request clef_list_choose(Button, EditorModel& model, std::optional<Time>);
    Request clef_edit_press(Button button, EditorModel&, std::optional<Time>);
    Request clef_name_press(Button button, EditorModel&, std::optional<Time>);
    Request clef_close_choose(Button, EditorModel&, std::optional<Time>);

    // Status texts that change (ModeRecord::live_hint).
    std::string browse_hint(const EditorModel& model) const;
    std::string entry_hint(const EditorModel& model) const;
    std::string name_hint(const EditorModel& model) const;
    std::string replace_hint(const EditorModel& model) const;
    std::string tapping_hint(const EditorModel& model) const;
    std::string use_for_hint(const EditorModel& model) const;
    std::string clef_edit_hint(const EditorModel& model) const;

    // What is drawn (ModeRecord::menu).
    MenuView main_menu_view(const EditorModel& model) const;
    MenuView clef_menu_view(const EditorModel& model) const;
    MenuView open_menu_view(const EditorModel& model) const;
    MenuView quit_menu_view(const EditorModel& model) const;
    MenuView name_view(const EditorModel& model) const;
    MenuView clef_list_view(const EditorModel& model) const;
    MenuView clef_name_view(const EditorModel& model) const;
    MenuView clef_close_view(const EditorModel& model) const;
    MenuView use_for_view(const EditorModel& model) const;
    MenuView no_events_view(const EditorModel& model) const;
    MenuView assigned_view(const EditorModel& model) const;
    MenuView replace_view(const EditorModel& model) const;

    // How many lines a list has (ModeRecord::choices).
    int bar_clef_choices(const EditorModel& model) const;
    int score_choices(const EditorModel& model) const;
    int three_choices(const EditorModel& model) const;
    int two_choices(const EditorModel& model) const;
    int event_choices(const EditorModel& model) const;
    int clef_choices(const EditorModel& model) const;

    // An action from the menu or a key: the session's own, or the model's (actions.hpp).
    Request perform(const Command& command, EditorModel& model);
    void open_clef_menu(const EditorModel& model);
    void open_score_list();
    Request ask_quit(const EditorModel& model);
    void leave_layers(EditorModel& model);
    // Back from a list begun while entering (a new bar's clef) goes on entering.
    bool entering_after_list(EditorModel& model);
    // Saves under `name`, or asks first when it is taken.
    Request save_under(const std::string& name, bool then_quit);
    void begin_name_entry(const EditorModel& model, bool then_quit);
    void begin_entry(EditorModel& model,
                     EditorModel::Continuing continuing = EditorModel::Continuing::no);
    void open_use_for(bool save_as);
    void open_clef_list(EditorModel& model);
    void begin_clef_name();
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

// What the status line shows now. `news` is what the last action did: shown while browsing or
// entering; in a menu, a list or browsing's other choices the hint wins over it (what was
// undone before opening the list says nothing about the list). While playing, the bar being
// played (`playing`), not the bar playback started from.
StatusParts status_of(const EditorModel& model, const ButtonScheme& scheme, const std::string& news,
                      std::optional<Position> playing = std::nullopt);

}  // namespace vibscore::editor
