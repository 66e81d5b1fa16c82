#include <cstdio>

#include "client/editor/button_scheme.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"

// The modes of editing clefs: which clef, its window, its new name, and closing it changed.
namespace vibscore::editor {

namespace {

Request hearing(const ClefEditor& editor) {
    Request request{Request::Kind::hear_clef, editor.id()};
    request.document = write_clef(editor.clef());
    request.string = editor.string();
    request.number = editor.number();
    return request;
}

}  // namespace

Request ButtonScheme::edit_clefs(EditorModel& model) {
    open_clef_list(model);
    return {};
}

// "edit clefs...": the clefs the session could read, the score's own first.
void ButtonScheme::open_clef_list(EditorModel& model) {
    if (clef_book_->clefs().empty()) {
        model.say("no clef could be read");
        return;
    }
    int index = 0;
    const std::string& current = model.score().bars.at(model.cursor().bar).clef;
    for (std::size_t i = 0; i < clef_book_->clefs().size(); ++i) {
        if (clef_book_->clefs()[i].declaration.id == current) {
            index = static_cast<int>(i);
        }
    }
    list_.set(index, static_cast<int>(clef_book_->clefs().size()));
    mode_ = Mode::clef_list;
}

int ButtonScheme::clef_choices(const EditorModel&) const {
    return static_cast<int>(clef_book_->clefs().size());
}

Request ButtonScheme::clef_list_choose(Button, EditorModel&, std::optional<Time>) {
    const auto& chosen = clef_book_->clefs()[static_cast<std::size_t>(list_.index())];
    clef_editor_ = ClefEditor(chosen.declaration.id, chosen.clef);
    mode_ = Mode::clef_edit;
    return {};
}

ButtonScheme::MenuView ButtonScheme::clef_list_view(const EditorModel&) const {
    MenuView view;
    view.title = "edit clefs";
    for (const auto& known : clef_book_->clefs()) {
        char tempo[32];
        std::snprintf(tempo, sizeof tempo, "%.2f s", known.clef.tempo);
        view.lines.push_back(known.declaration.id + "  " + std::string(to_string(known.clef.type)) +
                             " " + tempo);
    }
    view.highlighted = list_.index();
    return view;
}

Request ButtonScheme::clef_edit_press(Button button, EditorModel&, std::optional<Time>) {
    switch (clef_editor_.press(button)) {
        case ClefEditor::Outcome::editing:
            return {};
        case ClefEditor::Outcome::hear:
            return hearing(clef_editor_);
        case ClefEditor::Outcome::save_as:
            begin_clef_name();
            return {};
        case ClefEditor::Outcome::close:
            if (clef_editor_.modified()) {
                list_.set(0, 3);
                mode_ = Mode::clef_close;
                return {};
            }
            mode_ = Mode::browse;
            return {};
    }
    return {};
}

std::string ButtonScheme::clef_edit_hint(const EditorModel&) const {
    return clef_editor_.hint();
}

// A clef is saved under a new name each time: a shipped clef (or any other) is never saved
// over.
void ButtonScheme::begin_clef_name() {
    std::vector<std::string> names;
    for (const auto& known : clef_book_->clefs()) {
        names.push_back(known.declaration.id);
    }
    name_.start({free_name(clef_editor_.id(), names)});
    mode_ = Mode::clef_name;
}

Request ButtonScheme::clef_name_press(Button button, EditorModel&, std::optional<Time>) {
    switch (name_.press(button)) {
        case NameEntry::Outcome::typing:
            return {};
        case NameEntry::Outcome::cancelled:
            mode_ = Mode::clef_edit;
            return {};
        case NameEntry::Outcome::done:
            break;
    }
    if (clef_book_->find(name_.name()) != nullptr) {
        name_.refuse(name_.name() + " exists: another name");
        return {};
    }
    mode_ = Mode::browse;
    Request request{Request::Kind::save_clef, name_.name()};
    request.document = write_clef(clef_editor_.clef());
    return request;
}

ButtonScheme::MenuView ButtonScheme::clef_name_view(const EditorModel&) const {
    return {"save clef as", name_.lines(), name_.highlighted()};
}

Request ButtonScheme::clef_close_choose(Button, EditorModel&, std::optional<Time>) {
    switch (list_.index()) {
        case 0:
            begin_clef_name();
            return {};
        case 1:
            mode_ = Mode::browse;  // the changes dropped
            return {};
        default:
            mode_ = Mode::clef_edit;
            return {};
    }
}

ButtonScheme::MenuView ButtonScheme::clef_close_view(const EditorModel&) const {
    return {clef_editor_.id() + " changed",
            {"save as...", "drop the changes", "cancel"},
            list_.index()};
}

}  // namespace vibscore::editor
