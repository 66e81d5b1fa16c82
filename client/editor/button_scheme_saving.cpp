#include <algorithm>

#include "client/editor/button_scheme.hpp"

// The modes of saving: what the score is for (an event of the feedback theme), its name, a
// taken name, and the event once assigned.
namespace vibscore::editor {

namespace {

constexpr int kReplaceChoices = 3;  // another name, replace it, cancel

// Saving over a shipped score loses nothing (it stays, shadowed); over a stored score or a file
// the old one is gone. The question says which.
std::string replace_title(const TakenName& taken) {
    return taken.name + (taken.what == TakenName::What::shipped ? " is shipped" : " exists");
}

std::string replace_choice(const TakenName& taken) {
    return taken.what == TakenName::What::shipped ? "store yours over it" : "replace " + taken.name;
}

}  // namespace

Request ButtonScheme::save(EditorModel&) {
    asked_for_event_ = false;
    // A new score's first save asks what it is for, as save as does.
    if (never_saved_ && !events_->empty()) {
        open_use_for(false);
        return {};
    }
    pending_event_.clear();
    return save_under(destination_, false);
}

Request ButtonScheme::save_as(EditorModel& model) {
    asked_for_event_ = false;
    if (!events_->empty()) {
        open_use_for(true);
        return {};
    }
    pending_event_.clear();
    pending_save_as_ = true;
    begin_name_entry(model, false);
    return {};
}

Request ButtonScheme::use_for_event(EditorModel&) {
    open_event_choice();
    return {};
}

Request ButtonScheme::save_under(const std::string& name, bool then_quit) {
    const auto taken = std::find_if(taken_->begin(), taken_->end(),
                                    [&](const TakenName& taken) { return taken.name == name; });
    if (taken != taken_->end() && !(name == destination_ && destination_ours_)) {
        replacing_ = *taken;
        then_quit_ = then_quit;
        list_.set(0, kReplaceChoices);
        mode_ = Mode::replace_menu;
        return {};
    }
    mode_ = Mode::browse;
    if (name == destination_) {
        return {then_quit ? Request::Kind::save_and_quit : Request::Kind::save,
                {},
                0,
                false,
                pending_event_};
    }
    return {Request::Kind::save_as, name, 0, then_quit, pending_event_};
}

// Saving offers, before any name, the events the score could be for: the theme's events with
// what each plays now, and last, none.
void ButtonScheme::open_use_for(bool save_as) {
    pending_save_as_ = save_as;
    assign_only_ = false;
    asked_for_event_ = true;
    pending_event_.clear();
    list_.set(0, static_cast<int>(events_->size()) + 1);
    mode_ = Mode::use_for;
}

void ButtonScheme::open_event_choice() {
    if (events_->empty()) {
        list_.set(0, 1);
        mode_ = Mode::no_events;
        return;
    }
    pending_save_as_ = false;
    assign_only_ = true;
    pending_event_.clear();
    list_.set(0, static_cast<int>(events_->size()) + 1);
    mode_ = Mode::use_for;
}

void ButtonScheme::after_save(const std::string& event) {
    const bool asked = asked_for_event_;
    asked_for_event_ = false;
    if (!event.empty() || asked || events_->empty() || mode_ != Mode::browse) {
        return;
    }
    open_event_choice();
    // The offer comes unasked: Select on the line already chosen ("no event") goes on.
    list_.set(static_cast<int>(events_->size()), static_cast<int>(events_->size()) + 1);
}

int ButtonScheme::event_choices(const EditorModel&) const {
    return static_cast<int>(events_->size()) + 1;
}

Request ButtonScheme::use_for_choose(Button, EditorModel& model, std::optional<Time>) {
    const auto chosen = static_cast<std::size_t>(list_.index());
    if (assign_only_) {
        mode_ = Mode::browse;
        if (chosen >= events_->size()) {
            return {};
        }
        const std::string& event = (*events_)[chosen].event;
        if (model.modified() || never_saved_) {
            // What the event plays is what is stored: the changes are saved to the score's own
            // name first (a shipped one asks, as save does), never to a copy.
            pending_event_ = event;
            return save_under(destination_, false);
        }
        return {Request::Kind::assign_event, {}, 0, false, event};
    }
    if (chosen < events_->size()) {
        pending_event_ = (*events_)[chosen].event;  // a name proposed from it, one Select
        begin_name_entry(model, false);
        return {};
    }
    if (pending_save_as_) {
        begin_name_entry(model, false);
        return {};
    }
    return save_under(destination_, false);
}

std::string ButtonScheme::use_for_hint(const EditorModel&) const {
    return assign_only_ ? "\u2191\u2193choose Sel:use for it Back:close"
                        : "\u2191\u2193choose Sel:save for it Back:close";
}

ButtonScheme::MenuView ButtonScheme::use_for_view(const EditorModel&) const {
    MenuView view;
    view.title = assign_only_ ? "use " + destination_ + " for" : "use for ...";
    for (const auto& event : *events_) {
        view.lines.push_back(event_label(event.event) + ": " +
                             (event.score.empty() ? "-" : event.score));
    }
    view.lines.push_back(assign_only_       ? "no event"
                         : pending_save_as_ ? "no event: a name..."
                                            : "no event: just save");
    view.highlighted = list_.index();
    return view;
}

ButtonScheme::MenuView ButtonScheme::no_events_view(const EditorModel&) const {
    MenuView view;
    view.title = "use for event";
    // One line per sentence: the menu wraps them at the screen's width.
    std::string line;
    for (const char c : why_no_events_) {
        if (c == '\n') {
            view.lines.push_back(line);
            line.clear();
        } else {
            line += c;
        }
    }
    view.lines.push_back(line);
    view.highlighted = -1;
    return view;
}

void ButtonScheme::show_assigned(const std::string& event, const std::string& score) {
    assigned_before_ = {event, "", "", false};
    for (const auto& known : *events_) {
        if (known.event == event) {
            assigned_before_ = known;
        }
    }
    assigned_score_ = score;
    list_.set(0, 2);
    mode_ = Mode::assigned;
}

Request ButtonScheme::assigned_choose(Button, EditorModel& model, std::optional<Time>) {
    mode_ = Mode::browse;
    if (list_.index() == 0) {
        // Said after the question closes, by the event's own name (the one fbcli and the theme
        // use), so the line confirms what was done.
        model.say(assigned_before_.event + " plays " + assigned_score_);
        return {};
    }
    return {Request::Kind::keep_event, score_before(assigned_before_), 0, false,
            assigned_before_.event};
}

ButtonScheme::MenuView ButtonScheme::assigned_view(const EditorModel&) const {
    // Narrow screens: the title holds the event, the lines the two scores.
    return {
        event_label(assigned_before_.event) + " plays:",
        {assigned_score_ + " (ok)",
         "keep as it was (" +
             (assigned_before_.score.empty() ? std::string("-") : assigned_before_.score) + ")"},
        list_.index()};
}

void ButtonScheme::begin_name_entry(const EditorModel& model, bool then_quit) {
    std::vector<std::string> names;
    for (const auto& taken : *taken_) {
        names.push_back(taken.name);
    }
    auto proposals = name_proposals(destination_, model.score().title, pending_event_, names);
    if (never_saved_ && !pending_save_as_ && !pending_event_.empty()) {
        // Saving a new score for an event: its own name is one of the choices too.
        proposals.insert(proposals.begin() + 1, destination_);
    }
    name_.start(std::move(proposals));
    then_quit_ = then_quit;
    mode_ = Mode::name_entry;
}

Request ButtonScheme::name_press(Button button, EditorModel&, std::optional<Time>) {
    switch (name_.press(button)) {
        case NameEntry::Outcome::typing:
            return {};
        case NameEntry::Outcome::cancelled:
            mode_ = Mode::browse;
            return {};
        case NameEntry::Outcome::done:
            break;
    }
    // The name is what a save with it stores under, so a taken one asks before replacing it.
    return save_under(name_.name(), then_quit_);
}

// The name being typed, a score's or a clef's.
std::string ButtonScheme::name_hint(const EditorModel&) const {
    return name_.hint();
}

ButtonScheme::MenuView ButtonScheme::name_view(const EditorModel&) const {
    return {"save as", name_.lines(), name_.highlighted()};
}

Request ButtonScheme::replace_choose(Button, EditorModel& model, std::optional<Time>) {
    switch (list_.index()) {
        case 0:
            begin_name_entry(model, then_quit_);
            return {};
        case 1: {
            mode_ = Mode::browse;
            const std::string name = replacing_.name;
            if (name == destination_) {
                destination_ours_ = true;  // asked once; the next saves go there quietly
                return {then_quit_ ? Request::Kind::save_and_quit : Request::Kind::save,
                        {},
                        0,
                        false,
                        pending_event_};
            }
            return {Request::Kind::save_as, name, 0, then_quit_, pending_event_};
        }
        default:
            mode_ = Mode::browse;
            return {};
    }
}

std::string ButtonScheme::replace_hint(const EditorModel&) const {
    switch (replacing_.what) {
        case TakenName::What::shipped:
            return "\u2191\u2193choose Sel:ok (shipped file stays)";
        case TakenName::What::file:
            return "\u2191\u2193choose Sel:ok (old file is lost)";
        case TakenName::What::stored:
        case TakenName::What::stored_over_shipped:
            break;
    }
    return "\u2191\u2193choose Sel:ok (old one is lost)";
}

ButtonScheme::MenuView ButtonScheme::replace_view(const EditorModel&) const {
    return {replace_title(replacing_),
            {"save as another name", replace_choice(replacing_), "cancel"},
            list_.index()};
}

}  // namespace vibscore::editor
