#include <string>

#include "client/editor/button_scheme.hpp"

// The modes of moving about a score: browsing, its other choices, entering symbols, the menu,
// and playback.
namespace vibscore::editor {

namespace {

// Every hint fits the narrowest screen the editor supports (40x12) whole.
constexpr int kNarrowest = 40;

}  // namespace

Request ButtonScheme::stop(Button, EditorModel&, std::optional<Time>) {
    return {Request::Kind::stop};
}

Request ButtonScheme::begin_entry_step(Button, EditorModel& model, std::optional<Time>) {
    begin_entry(model);
    return {};
}

Request ButtonScheme::open_choices(Button, EditorModel& model, std::optional<Time>) {
    // What the last action did is old news: the line now says what the choices are (a
    // newcomer read "*crescendo" there, pressed Up to change the string and it played).
    model.clear_message();
    mode_ = Mode::browse_choices;
    return {};
}

// What Select and Back do while browsing, naming the symbol Select would change in words
// ("dotted 8th, 5, string 3"): the longest wording that fits the narrowest screen.
std::string ButtonScheme::browse_hint(const EditorModel& model) const {
    const Symbol* symbol = symbol_at(model.score(), model.cursor());
    if (symbol == nullptr) {
        return "S:new note B:play,go to,menu";
    }
    const std::string named = symbol_words(*symbol);
    for (const std::string& hint :
         {"S:change " + named + " B:play,go to,menu", "S:change " + named + " B:more"}) {
        if (columns_of(hint) <= kNarrowest) {
            return hint;
        }
    }
    return "S:" + named + " B:more";
}

Request ButtonScheme::entry(Button button, EditorModel& model, std::optional<Time>) {
    switch (steps_.press(button, model)) {
        case EntrySteps::Outcome::choosing:
            break;
        case EntrySteps::Outcome::done:
            model.end_entry();
            begin_entry(model, EditorModel::Continuing::yes);
            break;
        case EntrySteps::Outcome::new_bar:
            model.cancel_entry();
            model.split_bar();
            if (model.clef_choices().size() > 1) {
                // A new bar is where the clef changes, so its clef is asked for at once.
                open_clef_menu(model);
                enter_after_list_ = true;
            } else {
                begin_entry(model);
            }
            break;
        case EntrySteps::Outcome::leave:
            model.cancel_entry();
            mode_ = Mode::browse;
            break;
    }
    return {};
}

std::string ButtonScheme::entry_hint(const EditorModel& model) const {
    return steps_.hint(model);
}

void ButtonScheme::begin_entry(EditorModel& model, EditorModel::Continuing continuing) {
    if (model.begin_entry(continuing)) {
        steps_.start();
        mode_ = Mode::entry;
    }
}

Request ButtonScheme::menu_step(Button button, EditorModel& model, std::optional<Time>) {
    main_.step(button == Button::up ? -1 : +1, static_cast<int>(main_menu(model).size()));
    return {};
}

Request ButtonScheme::menu_group(Button button, EditorModel& model, std::optional<Time>) {
    main_.jump_group(button == Button::left ? -1 : +1, main_menu(model));
    return {};
}

Request ButtonScheme::menu_choose(Button, EditorModel& model, std::optional<Time>) {
    const auto entries = main_menu(model);
    mode_ = Mode::browse;
    return perform({entries[static_cast<std::size_t>(main_.index())].action}, model);
}

ButtonScheme::MenuView ButtonScheme::main_menu_view(const EditorModel& model) const {
    MenuView view;
    const auto entries = main_menu(model);
    for (const auto& entry : entries) {
        view.lines.push_back(entry.label);
    }
    view.highlighted = main_.index();
    const MenuGroup group = entries[static_cast<std::size_t>(view.highlighted)].group;
    view.title = "menu: " + std::string(group_name(group)) + " " +
                 std::to_string(static_cast<int>(group) + 1) + "/" +
                 std::to_string(menu_group_count);
    return view;
}

}  // namespace vibscore::editor
