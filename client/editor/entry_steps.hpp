#pragma once

#include <string>

#include "client/editor/buttons.hpp"
#include "client/editor/editor_model.hpp"

namespace vibscore::editor {

// Entering one symbol with the six buttons, in up to three steps: its string, its number, its
// length. Every press chooses and most move on, so a changed note costs one press per thing
// that changes. In every step Select enters the symbol as shown, Up and Down change this step's
// part by one, Right and Left by two, and Back turns to the step's other choices (Back there
// turns back), where Select keeps this part and goes on to the next step.
//   string          Select: the whole symbol as shown, done   Up/Down/Right/Left: +1 -1 +2 -2
//   string, more    Select: this string   Up: the opposite string (+3)   Down: a rest, done
//                   Left: a rest of another length   Right: a new bar here   Back: leave entry
//   number          Select: done   Up/Down/Right/Left: +1 -1 +2 -2
//   number, more    Select: this number   Up/Down/Right/Left: +3 -3 +4 -4
//   length          Up/Down/Right/Left: longer, shorter, two longer, two shorter: done
//                   more: Up dotted or not, Down the marks, Right/Left three longer/shorter
//   marks           Up legato with the note before, Down portamento, Left decrescendo,
//                   Right crescendo (each again takes it off)
// docs/editor.md has the reasoning and the measured presses.
class EntrySteps {
  public:
    enum class Step { string, string_more, number, number_more, length, length_more, marks };
    enum class Outcome {
        choosing,  // still choosing this symbol
        done,      // this symbol is entered: on to the next
        new_bar,   // drop the symbol being chosen, start a bar here, go on there
        leave,     // drop the symbol being chosen and stop entering
    };

    void start() { step_ = Step::string; }
    Step step() const { return step_; }
    Outcome press(Button button, EditorModel& model);
    // What each button does in this step, with the values it gives (fits 40 columns with the
    // symbol's own description before it).
    std::string hint(const EditorModel& model) const;

    bool operator==(const EntrySteps&) const = default;

  private:
    Outcome string_step(Button button, EditorModel& model);
    Outcome string_more(Button button, EditorModel& model);
    Outcome number_step(Button button, EditorModel& model);
    Outcome length_step(Button button, EditorModel& model);
    Outcome length_more(Button button, EditorModel& model);
    Outcome marks(Button button, EditorModel& model);
    // After the string: a note's number next, a rest has none.
    Outcome after_string(const EditorModel& model);

    Step step_ = Step::string;
};

}  // namespace vibscore::editor
