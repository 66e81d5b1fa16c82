#pragma once

#include <optional>
#include <string>
#include <vector>

#include "client/editor/commands.hpp"
#include "client/editor/phrase_book.hpp"
#include "client/editor/position.hpp"
#include "client/editor/score_edits.hpp"
#include "client/editor/shared_value.hpp"
#include "client/editor/undo_history.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// The score being edited, the editing cursor (a position and the active string, thesis §4.2),
// the block, the clipboard and undo. Every editing function of thesis Fig. 4.3 is a method here;
// keys and buttons only choose which. A refused edit changes nothing and says why in message().
// A value type, compared by value: the press planner copies whole editors and tells states
// apart by ==.
class EditorModel {
  public:
    // `available_clefs` are the clefs a bar may be given besides those the score declares.
    explicit EditorModel(Score score, std::vector<ClefDeclaration> available_clefs = {});

    // A score with one empty bar played with `clef`.
    static Score blank_score(std::string title, const ClefDeclaration& clef);

    const Score& score() const { return *score_; }
    Position cursor() const { return cursor_; }
    int string() const { return string_; }
    Length current_length() const { return length_; }
    int current_number() const { return number_; }
    // The marked block, when it holds at least one position.
    std::optional<Block> block() const;
    bool marking() const { return anchor_.has_value(); }
    const std::vector<ClefDeclaration>& available_clefs() const { return *available_clefs_; }
    // Every clef a bar may use: the declared ones, then the available ones not declared.
    std::vector<ClefDeclaration> clef_choices() const;
    const std::string& message() const { return message_; }
    // What was done is old news once the buttons turn to something else.
    void clear_message() { message_.clear(); }
    // News from around the model (a rhythm tapped, a clef chosen) on the same line.
    void say(std::string news) { message_ = std::move(news); }
    bool modified() const { return *score_ != *saved_; }
    void mark_saved() { saved_ = score_; }
    void set_title(std::string title);
    // What a session keeps when another score is opened or a new one started: the clipboard,
    // so a bar copied in one score can be pasted into another.
    void carry_over(const EditorModel& previous) { clipboard_ = previous.clipboard_; }
    // A clef bars may use from now on (one just saved).
    void add_available_clef(const ClefDeclaration& clef);
    // The scores the proposals learn from besides the score itself (phrase_book.hpp).
    void learn_from(std::shared_ptr<const PhraseBook> phrases) { phrases_ = std::move(phrases); }

    // What the six-button entry puts on an empty position: what followed the symbol before it
    // where it came earlier (recurrence.hpp), else what followed the last two or more symbols in
    // a score learned from (phrase_book.hpp), else proposed_note().
    Symbol proposed_symbol() const;
    // The note proposed when the score does not say which: the last-used number and length on
    // the active string with the hairpin of the last note, the ties of a note directly before,
    // and the step in number between the two notes directly before (a fade goes on fading).
    Note proposed_note() const;
    // Where the symbol being entered is not what entering ran on with: a length other than the
    // last note's (a rest's: the last rest's), a string other than the active one. A proposal
    // that changes either is shown so, not to be taken by a thumb used to the last one.
    struct Unlike {
        bool length = false;
        bool string = false;
    };
    Unlike unlike_last_entered() const;
    // The note or rest the symbol functions act on: the one under the cursor, or on an empty
    // position the one just before it.
    std::optional<Position> at_hand() const;

    // Keyboard-level commands (Fig. 4.3). Returns false, with message(), when refused.
    bool apply(const Command& command);

    void move_left();
    void move_right();
    void move_up();
    void move_down();
    void to_first_bar();  // the first position of the score
    void to_last_bar();   // the end of the last bar
    void extend(int direction);
    bool insert_note(int number);
    bool insert_rest();
    bool insert_blank();
    bool split_bar();
    bool delete_at_cursor();
    bool set_dynamics(Dynamics dynamics);
    bool tie(Tie tie);
    bool untie(Tie tie);
    bool set_length(Length length);
    bool set_length_value(int value);  // a Length by its index, as a key gives it
    bool toggle_dot();
    bool shift_strings(int delta);
    bool shift_numbers(int delta);
    void mark_block();
    void clear_block();
    bool copy();
    bool cut();
    bool paste();
    bool undo();
    bool redo();
    bool set_bar_clef(const std::string& id);
    // Bars `first` to `last` play with `clef` (declared when the score does not yet).
    bool set_clef_of_bars(std::size_t first, std::size_t last, const ClefDeclaration& clef);
    // Whole bars (a tapped rhythm) put in as bars at the cursor, one undo step: an empty bar is
    // replaced by them, at a bar line they go in before or after the bar, inside a bar it is
    // split there. The cursor goes to their first symbol. A clef they use that the score does
    // not declare (a tapped rhythm's tempo clef, made available first) is declared with them.
    bool insert_bars(const std::vector<Bar>& bars);

    // The six-button entry of one symbol, undone as one step: begin_entry puts the proposed
    // symbol on an empty position (or takes the symbol under the cursor); the entry_ functions
    // change it; end_entry keeps it and moves the cursor past it, cancel_entry takes it back.
    // Continuing an entry at the end of a full bar goes on at the start of the next bar, a new
    // one after the last bar.
    enum class Continuing { no, yes };
    bool begin_entry(Continuing continuing = Continuing::no);
    // Moves the note `delta` strings up, wrapping round the six; a rest becomes the proposed
    // note there. The active string follows.
    void entry_string(int delta);
    void entry_number(int delta);  // wraps round 1..9
    void entry_length(int delta);  // > 0 longer, < 0 shorter, one length per step
    // Makes it a rest, as long as the last rest entered (or the current length before any).
    void entry_rest();
    void entry_toggle_dot();
    void entry_dynamics(Dynamics dynamics);  // this hairpin, or none if it already has it
    void entry_tie(Tie tie);                 // tied to the note before, or untied if it was
    void end_entry();
    void cancel_entry();
    // While entering: whether the symbol open is one the score had (being changed), not a
    // proposal for an empty position.
    bool changing() const { return in_entry_ && !entry_proposed_; }

    // Every part of the state, compared by value: two editors that are equal answer every key
    // and button alike (the press planner relies on it; tests/unit/editor_state_test.cpp).
    bool operator==(const EditorModel&) const = default;

  private:
    Score& edit();  // records the state for undo, then gives the score to change
    Snapshot snapshot() const;
    void restore(const Snapshot& snapshot);
    std::vector<Position> targets() const;  // the block's notes and rests, or the one at hand
    std::vector<Position> target_notes() const;
    void jump_to(Position position);  // a move as the arrows make one, any distance
    void step_left();
    bool step_right();  // false at the end of the score
    void land();        // keeps the cursor valid and lets the active string follow a note under it
    // The next proposal's length: a note's for notes, a rest's for rests.
    void remember_length(const Symbol& entered, Length length);
    bool at_end_of_full_bar() const;
    bool refuse(std::string why);
    bool done(std::string what);

    Shared<Score> score_;
    Shared<Score> saved_;
    Shared<std::vector<ClefDeclaration>> available_clefs_;
    std::shared_ptr<const PhraseBook> phrases_;
    UndoHistory history_;
    Position cursor_;
    int string_ = 3;
    Length length_ = Length::quarter;
    int number_ = 5;
    std::optional<Length> rest_length_;  // the last rest the buttons entered
    std::optional<Position> anchor_;
    bool anchor_sticky_ = false;  // marked from a menu: moving grows the block
    Clip clipboard_;
    bool in_entry_ = false;
    bool entry_proposed_ = false;  // the open symbol is a proposal, not one the score had
    std::string message_;
};

}  // namespace vibscore::editor
