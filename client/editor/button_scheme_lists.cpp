#include "client/editor/button_scheme.hpp"

// The lists of choices: a bar's clef, the scores to open, what quitting with changes does; and
// the Up/Down every list shares.
namespace vibscore::editor {

namespace {

const char* kQuitChoices[] = {"save and quit", "quit without saving", "cancel"};

}  // namespace

// Up and Down move through the mode's list, wrapping.
Request ButtonScheme::list_step(Button button, EditorModel& model, std::optional<Time>) {
    list_.step(button == Button::up ? -1 : 1, (this->*record().choices)(model));
    return {};
}

bool ButtonScheme::entering_after_list(EditorModel& model) {
    if (!enter_after_list_) {
        return false;
    }
    enter_after_list_ = false;
    begin_entry(model);
    return true;
}

Request ButtonScheme::list_back_to_menu(Button, EditorModel& model, std::optional<Time>) {
    if (!entering_after_list(model)) {
        mode_ = Mode::menu;
    }
    return {};
}

Request ButtonScheme::list_back_to_browse(Button, EditorModel& model, std::optional<Time>) {
    if (!entering_after_list(model)) {
        mode_ = Mode::browse;
    }
    return {};
}

int ButtonScheme::bar_clef_choices(const EditorModel& model) const {
    return static_cast<int>(model.clef_choices().size());
}

int ButtonScheme::score_choices(const EditorModel&) const {
    return static_cast<int>(openable_->size());
}

int ButtonScheme::three_choices(const EditorModel&) const {
    return 3;
}

int ButtonScheme::two_choices(const EditorModel&) const {
    return 2;
}

Request ButtonScheme::choose_clef(EditorModel& model) {
    open_clef_menu(model);
    return {};
}

void ButtonScheme::open_clef_menu(const EditorModel& model) {
    const auto choices = model.clef_choices();
    const std::string& current = model.score().bars.at(model.cursor().bar).clef;
    int index = 0;
    for (std::size_t i = 0; i < choices.size(); ++i) {
        if (choices[i].id == current) {
            index = static_cast<int>(i);
        }
    }
    list_.set(index, static_cast<int>(choices.size()));
    mode_ = Mode::clef_menu;
}

Request ButtonScheme::choose_bar_clef(Button, EditorModel& model, std::optional<Time>) {
    mode_ = Mode::browse;
    if (bar_clef_choices(model) == 0) {
        return {};
    }
    model.set_bar_clef(model.clef_choices()[static_cast<std::size_t>(list_.index())].id);
    entering_after_list(model);
    return {};
}

ButtonScheme::MenuView ButtonScheme::clef_menu_view(const EditorModel& model) const {
    MenuView view;
    view.title = "clef of bar " + std::to_string(model.cursor().bar + 1);
    for (const auto& clef : model.clef_choices()) {
        view.lines.push_back(clef.id + "  " + clef.href);
    }
    view.highlighted = list_.index();
    return view;
}

Request ButtonScheme::open(EditorModel&) {
    open_score_list();
    return {};
}

void ButtonScheme::open_score_list() {
    if (openable_->empty()) {
        return;
    }
    list_.set(last_open_, static_cast<int>(openable_->size()));
    mode_ = Mode::open_menu;
}

Request ButtonScheme::choose_score(Button, EditorModel&, std::optional<Time>) {
    mode_ = Mode::browse;
    if (openable_->empty()) {
        return {};
    }
    last_open_ = list_.index();
    return {Request::Kind::open, (*openable_)[static_cast<std::size_t>(list_.index())]};
}

ButtonScheme::MenuView ButtonScheme::open_menu_view(const EditorModel&) const {
    return {"open", *openable_, list_.index()};
}

Request ButtonScheme::quit(EditorModel& model) {
    return ask_quit(model);
}

Request ButtonScheme::ask_quit(const EditorModel& model) {
    if (!model.modified()) {
        return {Request::Kind::quit};
    }
    list_.set(0, 3);
    mode_ = Mode::quit_menu;
    return {};
}

Request ButtonScheme::choose_quit(Button, EditorModel&, std::optional<Time>) {
    mode_ = Mode::browse;
    switch (list_.index()) {
        case 0:
            return save_under(destination_, true);
        case 1:
            return {Request::Kind::quit};
        default:
            return {};
    }
}

ButtonScheme::MenuView ButtonScheme::quit_menu_view(const EditorModel&) const {
    return {"unsaved changes", {std::begin(kQuitChoices), std::end(kQuitChoices)}, list_.index()};
}

}  // namespace vibscore::editor
