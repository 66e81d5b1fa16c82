#include "client/editor/entry_steps.hpp"

#include <set>

#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

namespace {

// The change Up, Down, Right and Left make in the string, number and length steps.
int delta_of(Button button) {
    switch (button) {
        case Button::up:
            return +1;
        case Button::down:
            return -1;
        case Button::right:
            return +2;
        case Button::left:
            return -2;
        default:
            return 0;
    }
}

const Note* note_entered(const EditorModel& model) {
    return note_at(model.score(), model.cursor());
}

Length length_entered(const EditorModel& model) {
    const Symbol* symbol = symbol_at(model.score(), model.cursor());
    return symbol ? length_of(*symbol) : model.current_length();
}

}  // namespace

EntrySteps::Outcome EntrySteps::press(Button button, EditorModel& model) {
    switch (step_) {
        case Step::string:
            return string_step(button, model);
        case Step::string_more:
            return string_more(button, model);
        case Step::number:
        case Step::number_more:
            return number_step(button, model);
        case Step::length:
            return length_step(button, model);
        case Step::length_more:
            return length_more(button, model);
        case Step::marks:
            return marks(button, model);
    }
    return Outcome::choosing;
}

EntrySteps::Outcome EntrySteps::after_string(const EditorModel& model) {
    step_ = note_entered(model) ? Step::number : Step::length;
    return Outcome::choosing;
}

EntrySteps::Outcome EntrySteps::string_step(Button button, EditorModel& model) {
    switch (button) {
        case Button::select:
            return Outcome::done;
        case Button::back:
            step_ = Step::string_more;
            return Outcome::choosing;
        default:
            model.entry_string(delta_of(button));
            return after_string(model);
    }
}

EntrySteps::Outcome EntrySteps::string_more(Button button, EditorModel& model) {
    switch (button) {
        case Button::select:
            model.entry_string(0);
            return after_string(model);
        case Button::up:
            model.entry_string(+3);
            return after_string(model);
        case Button::down:
            model.entry_rest();
            return Outcome::done;
        case Button::left:
            model.entry_rest();
            step_ = Step::length;
            return Outcome::choosing;
        case Button::right:
            return Outcome::new_bar;
        case Button::back:
            return Outcome::leave;
    }
    return Outcome::choosing;
}

EntrySteps::Outcome EntrySteps::number_step(Button button, EditorModel& model) {
    const bool more = step_ == Step::number_more;
    switch (button) {
        case Button::back:
            step_ = more ? Step::number : Step::number_more;
            return Outcome::choosing;
        case Button::select:
            if (more) {
                step_ = Step::length;  // this number; the length is still to choose
                return Outcome::choosing;
            }
            return Outcome::done;  // as in every step, Select enters what is shown
        default:
            break;
    }
    const int delta = delta_of(button);
    model.entry_number(more ? delta + (delta > 0 ? 2 : -2) : delta);
    step_ = Step::length;
    return Outcome::choosing;
}

EntrySteps::Outcome EntrySteps::length_step(Button button, EditorModel& model) {
    if (button == Button::back) {
        step_ = Step::length_more;
        return Outcome::choosing;
    }
    // Up and Down one length, Right and Left two: longer to the right, as on the staff.
    const int delta = delta_of(button);
    model.entry_length(delta);
    return Outcome::done;
}

EntrySteps::Outcome EntrySteps::length_more(Button button, EditorModel& model) {
    switch (button) {
        case Button::up:
            model.entry_toggle_dot();
            step_ = Step::length;
            return Outcome::choosing;
        case Button::down:
            step_ = note_entered(model) ? Step::marks : Step::length;
            return Outcome::choosing;
        case Button::right:
            model.entry_length(+3);
            return Outcome::done;
        case Button::left:
            model.entry_length(-3);
            return Outcome::done;
        case Button::select:
        case Button::back:
            step_ = Step::length;
            return Outcome::choosing;
    }
    return Outcome::choosing;
}

EntrySteps::Outcome EntrySteps::marks(Button button, EditorModel& model) {
    switch (button) {
        case Button::up:
            model.entry_tie(Tie::legato);
            break;
        case Button::down:
            model.entry_tie(Tie::portamento);
            break;
        case Button::left:
            model.entry_dynamics(Dynamics::decrescendo);
            break;
        case Button::right:
            model.entry_dynamics(Dynamics::crescendo);
            break;
        case Button::select:
        case Button::back:
            break;
    }
    step_ = Step::length;
    return Outcome::choosing;
}

std::string EntrySteps::hint(const EditorModel& model) const {
    const Note* note = note_entered(model);
    const int string = note ? note->string : model.string();
    const int number = note ? note->number : model.current_number();
    const Length length = length_entered(model);
    const auto s = [&](int delta) {
        return "s" + std::to_string(wrapped(string, delta, lowest_string, highest_string));
    };
    const auto number_at = [&](int delta) {
        return wrapped(number, delta, lowest_number, highest_number);
    };
    const auto n = [&](int delta) { return std::to_string(number_at(delta)); };
    const auto l = [&](int delta) { return length_name(stepped(length, delta)); };
    switch (step_) {
        case Step::string:
            return "\u2191" + s(1) + " \u2193" + s(-1) + " \u2192" + s(2) + " \u2190" + s(-2) +
                   " S:ok B:more";
        case Step::string_more:
            return "\u2191" + s(3) + " S:" + s(0) + " \u2193rest \u2190rest.. \u2192bar B:leave";
        case Step::number: {
            // Back's four numbers named here too, so every number is on the screen.
            std::set<int> behind_back{number_at(3), number_at(-3), number_at(4), number_at(-4)};
            std::string others;
            for (const int other : behind_back) {
                others += (others.empty() ? "" : ",") + std::to_string(other);
            }
            return "\u2191" + n(1) + " \u2193" + n(-1) + " \u2192" + n(2) + " \u2190" + n(-2) +
                   " S:ok B:" + others;
        }
        case Step::number_more:
            return "\u2191" + n(3) + " \u2193" + n(-3) + " \u2192" + n(4) + " \u2190" + n(-4) +
                   " S:len B:back";
        case Step::length:
            return "\u2191" + l(1) + " \u2193" + l(-1) + " \u2192" + l(2) + " \u2190" + l(-2) +
                   " S:ok B:more";
        case Step::length_more:
            return "\u2191dot \u2193marks \u2192" + l(3) + " \u2190" + l(-3) + " B:back";
        case Step::marks:
            return "\u2191legato \u2193port \u2190> \u2192< B:back";
    }
    return {};
}

}  // namespace vibscore::editor
