#include "client/editor/button_scheme.hpp"

#include "client/editor/actions.hpp"

// The scheme's dispatch: each question about the buttons is a look-up in the mode table
// (mode_table.cpp); the steps the table names live beside the modes they serve
// (button_scheme_*.cpp).
namespace vibscore::editor {

namespace {

constexpr const char* kOnlyNameCharacters = "names take a-z 0-9 . _ -; Enter saves";

}  // namespace

const ButtonScheme::ModeRecord& ButtonScheme::mode_record(Mode mode) {
    return modes()[static_cast<std::size_t>(mode)];
}

Request ButtonScheme::press(Button button, EditorModel& model, std::optional<Time> at) {
    const ButtonUse& use = record().buttons[static_cast<std::size_t>(button)];
    if (use.then) {
        mode_ = *use.then;
    }
    if (use.step != nullptr) {
        return (this->*use.step)(button, model, at);
    }
    if (use.action != Action::end) {
        return perform({use.action}, model);
    }
    return {};
}

void ButtonScheme::release(Button button, Time at) {
    if (mode_ == Mode::tapping && button == Button::select) {
        taps_.release_select(at);
    }
}

void ButtonScheme::set_playing(bool playing) {
    if (playing) {
        mode_ = Mode::playing;
    } else if (mode_ == Mode::playing) {
        mode_ = Mode::browse;
    }
}

bool ButtonScheme::typing_a_name() const {
    return record().keyboard == Keyboard::typing;
}

const ClefEditor* ButtonScheme::clef_editor() const {
    return record().clef_window ? &clef_editor_ : nullptr;
}

Request ButtonScheme::command(const Command& command, EditorModel& model) {
    switch (record().keyboard) {
        case Keyboard::stop:
            return {Request::Kind::stop};
        case Keyboard::typing:
            // A letter's action would leave the name half typed (at 80x24 every letter is one).
            model.say(kOnlyNameCharacters);
            return {};
        case Keyboard::clef_open:
            // A letter key at 80x24 would otherwise drop the clef being edited without a word.
            model.say("a clef is open: Back, Back closes it");
            return {};
        case Keyboard::leave:
            break;
    }
    leave_layers(model);
    return perform(command, model);
}

Request ButtonScheme::type_key(char c, EditorModel& model) {
    if (!name_.type_key(c)) {
        model.say(kOnlyNameCharacters);
    }
    return {};
}

ButtonScheme::MenuView ButtonScheme::menu_view(const EditorModel& model) const {
    const auto menu = record().menu;
    return menu != nullptr ? (this->*menu)(model) : MenuView{};
}

std::string ButtonScheme::hint(const EditorModel& model) const {
    // Short enough to share a 40-column status line with what is being entered.
    const ModeRecord& mode = record();
    return mode.live_hint != nullptr ? (this->*mode.live_hint)(model) : std::string(mode.hint);
}

Request ButtonScheme::perform(const Command& command, EditorModel& model) {
    const auto& record = record_of(command.action);
    if (record.session != nullptr) {
        return record.session(*this, model);
    }
    model.apply(command);
    return {};
}

void ButtonScheme::leave_layers(EditorModel& model) {
    if (mode_ == Mode::entry) {
        model.cancel_entry();
    }
    mode_ = Mode::browse;
    enter_after_list_ = false;
    taps_ = {};
}

StatusParts status_of(const EditorModel& model, const ButtonScheme& scheme, const std::string& news,
                      std::optional<Position> playing) {
    const ButtonScheme::Mode mode = scheme.mode();
    if (mode == ButtonScheme::Mode::playing) {
        // "playing bar 1" read as "now in bar 1" while the cursor moved through bar 4: the bar
        // is the one playing now.
        std::string hint = scheme.hint(model);
        if (playing) {
            hint = "playing bar " + std::to_string(playing->bar + 1) + "/" +
                   std::to_string(model.score().bars.size()) + ": any button stops";
        }
        return {model.modified(), "", "", hint, 0, 0};
    }
    return {model.modified(),
            ButtonScheme::mode_record(mode).news_shown ? news : "",
            mode == ButtonScheme::Mode::entry ? symbol_entered(model) : "",
            scheme.hint(model),
            model.cursor().bar + 1,
            model.score().bars.size()};
}

}  // namespace vibscore::editor
