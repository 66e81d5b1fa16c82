#include "client/editor/button_scheme.hpp"

#include <algorithm>
#include <cstdio>

#include "client/editor/actions.hpp"
#include "client/editor/status_line.hpp"
#include "client/formats/score_builder.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"

namespace vibscore::editor {

namespace {

// Every hint fits the narrowest screen the editor supports (40x12) whole.
constexpr int kNarrowest = 40;

const char* kQuitChoices[] = {"save and quit", "quit without saving", "cancel"};
constexpr int kReplaceChoices = 3;  // another name, replace it, cancel
constexpr const char* kOnlyNameCharacters = "names take a-z 0-9 . _ -; Enter saves";

// Saving over a shipped score loses nothing (it stays, shadowed); over a stored score or a file
// the old one is gone. The question says which.
std::string replace_title(const TakenName& taken) {
    return taken.name + (taken.what == TakenName::What::shipped ? " is shipped" : " exists");
}

std::string replace_choice(const TakenName& taken) {
    return taken.what == TakenName::What::shipped ? "store yours over it" : "replace " + taken.name;
}

std::string replace_hint(const TakenName& taken) {
    switch (taken.what) {
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

// What Select and Back do while browsing, naming the symbol Select would change in words
// ("dotted 8th, 5, string 3"): the longest wording that fits the narrowest screen.
std::string browse_hint(const EditorModel& model) {
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

}  // namespace

void ButtonScheme::set_playing(bool playing) {
    if (playing) {
        mode_ = Mode::playing;
    } else if (mode_ == Mode::playing) {
        mode_ = Mode::browse;
    }
}

Request ButtonScheme::press(Button button, EditorModel& model, std::optional<Time> at) {
    switch (mode_) {
        case Mode::tapping:
            return tap(button, model, at);
        case Mode::browse:
            return browse(button, model);
        case Mode::browse_choices:
            return browse_choices(button, model);
        case Mode::entry:
            return entry(button, model);
        case Mode::menu:
            return main_menu_press(button, model);
        case Mode::clef_menu:
        case Mode::open_menu:
        case Mode::quit_menu:
            return list_press(button, model);
        case Mode::name_entry:
            return name_press(button);
        case Mode::replace_menu:
            return replace_press(button, model);
        case Mode::use_for:
            return use_for_press(button, model);
        case Mode::clef_list:
            return clef_list_press(button, model);
        case Mode::clef_edit:
            return clef_edit_press(button);
        case Mode::clef_name:
            return clef_name_press(button);
        case Mode::clef_close:
            return clef_close_press(button);
        case Mode::assigned:
            return assigned_press(button, model);
        case Mode::no_events:
            if (button == Button::select || button == Button::back) {
                mode_ = Mode::browse;
            }
            return {};
        case Mode::playing:
            return {Request::Kind::stop};
    }
    return {};
}

void ButtonScheme::release(Button button, Time at) {
    if (mode_ == Mode::tapping && button == Button::select) {
        taps_.release_select(at);
    }
}

// Select taps a note, Down a rest; Up or Back ends tapping and writes the rhythm, Left drops
// it. Presses without a time (the press planner's) tap nothing.
Request ButtonScheme::tap(Button button, EditorModel& model, std::optional<Time> at) {
    switch (button) {
        case Button::select:
            if (at) {
                taps_.press_select(*at);
            }
            return {};
        case Button::down:
            if (at) {
                taps_.press_rest(*at);
            }
            return {};
        case Button::up:
        case Button::back:
            if (at) {
                taps_.finish(*at);
            }
            return end_tapping(model);
        case Button::left:
            taps_ = {};
            mode_ = Mode::browse;
            model.say("tapping dropped");
            return {};
        case Button::right:
            return {};
    }
    return {};
}

// A rhythm tapped at another pace than its bar's clef plays at that pace: on a copy of the
// clef at the tapped tempo, named as the importers name theirs (lra-phone-150bpm), made once
// and found again when another rhythm is tapped at that tempo.
Request ButtonScheme::end_tapping(EditorModel& model) {
    mode_ = Mode::browse;
    const auto sounds = taps_.sounds();
    taps_ = {};
    if (sounds.empty()) {
        model.say("nothing tapped");
        return {};
    }
    const std::string& clef = model.score().bars.at(model.cursor().bar).clef;
    const KnownClef* known = clef_book_->find(clef);
    const double clef_tempo = known ? known->clef.tempo : 0.0;
    const Note proposed = model.proposed_note();
    try {
        auto rhythm = tapped_rhythm(sounds, clef_tempo, clef, proposed.string, proposed.number);
        char tempo[32];
        std::snprintf(tempo, sizeof tempo, "%.2f", rhythm.tempo);
        std::string said = std::to_string(rhythm.notes) + " notes at " + tempo + " s a beat";
        Request request;
        if (known != nullptr && rhythm.tempo != clef_tempo) {
            Clef copy = known->clef;
            copy.tempo = rhythm.tempo;
            std::string id =
                formats::clef_id_for({known->declaration.id, known->clef}, rhythm.tempo);
            // A copy made before (perhaps under a free name, beside another clef of this name).
            const KnownClef* found = clef_book_->find(id);
            for (const auto& each : clef_book_->clefs()) {
                if (each.clef == copy && each.declaration.id.starts_with(id)) {
                    found = &each;
                    id = each.declaration.id;
                    break;
                }
            }
            if (found == nullptr || found->clef != copy) {
                if (found != nullptr) {
                    std::vector<std::string> names;
                    for (const auto& each : clef_book_->clefs()) {
                        names.push_back(each.declaration.id);
                    }
                    id = free_name(id, names);
                }
                const ClefDeclaration declaration{id, id + std::string(kClefSuffix)};
                add_clef({declaration, copy, false});
                request = {Request::Kind::store_clef, id};
                request.document = write_clef(copy);
            }
            model.add_available_clef(clef_book_->find(id)->declaration);
            for (auto& bar : rhythm.bars) {
                bar.clef = id;
            }
            // The clef first: on a 40-column line the tempo it plays at is what must show.
            said = std::to_string(rhythm.notes) + " notes, clef " + id + " (" + tempo + " s)";
        } else {
            said += ": S changes";
        }
        model.insert_bars(rhythm.bars);
        model.say(said);
        return request;
    } catch (const std::exception& error) {
        model.say(std::string("not tapped: ") + error.what());
    }
    return {};
}

Request ButtonScheme::browse(Button button, EditorModel& model) {
    switch (button) {
        case Button::up:
            model.move_up();
            break;
        case Button::down:
            model.move_down();
            break;
        case Button::left:
            model.move_left();
            break;
        case Button::right:
            model.move_right();
            break;
        case Button::select:
            begin_entry(model);
            break;
        case Button::back:
            // What the last action did is old news: the line now says what the choices are
            // (a newcomer read "*crescendo" there, pressed Up to change the string and it played).
            model.clear_message();
            mode_ = Mode::browse_choices;
            break;
    }
    return {};
}

// Going back to the start, to the end and playing are what a composer does between every few
// symbols, so they are two presses from browsing rather than a walk through the menu.
Request ButtonScheme::browse_choices(Button button, EditorModel& model) {
    mode_ = Mode::browse;
    switch (button) {
        case Button::up:
            return perform({Action::play_from_start}, model);
        case Button::down:
            return perform({Action::play_or_stop}, model);
        case Button::left:
            return perform({Action::to_first_bar}, model);
        case Button::right:
            return perform({Action::to_last_bar}, model);
        case Button::select:
            mode_ = Mode::menu;
            return {};
        case Button::back:
            return {};
    }
    return {};
}

Request ButtonScheme::entry(Button button, EditorModel& model) {
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

void ButtonScheme::begin_entry(EditorModel& model, EditorModel::Continuing continuing) {
    if (model.begin_entry(continuing)) {
        steps_.start();
        mode_ = Mode::entry;
    }
}

Request ButtonScheme::main_menu_press(Button button, EditorModel& model) {
    const auto entries = main_menu(model);
    const int size = static_cast<int>(entries.size());
    switch (button) {
        case Button::up:
            main_.step(-1, size);
            break;
        case Button::down:
            main_.step(+1, size);
            break;
        case Button::left:
            main_.jump_group(-1, entries);
            break;
        case Button::right:
            main_.jump_group(+1, entries);
            break;
        case Button::back:
            mode_ = Mode::browse;
            break;
        case Button::select:
            mode_ = Mode::browse;
            return perform({entries[static_cast<std::size_t>(main_.index())].action}, model);
    }
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

// The buttons of every list of choices: Up and Down move through `size` choices, Left and Right
// do nothing, Back goes to `back_to`. True for Select, whose choice the caller carries out.
bool ButtonScheme::choosing(Button button, int size, Mode back_to) {
    switch (button) {
        case Button::up:
        case Button::down:
            list_.step(button == Button::up ? -1 : 1, size);
            return false;
        case Button::left:
        case Button::right:
            return false;
        case Button::back:
            mode_ = back_to;
            return false;
        case Button::select:
            return true;
    }
    return false;
}

Request ButtonScheme::list_press(Button button, EditorModel& model) {
    const int size = mode_ == Mode::clef_menu   ? static_cast<int>(model.clef_choices().size())
                     : mode_ == Mode::open_menu ? static_cast<int>(openable_->size())
                                                : 3;
    switch (button) {
        case Button::up:
            list_.step(-1, size);
            return {};
        case Button::down:
            list_.step(+1, size);
            return {};
        case Button::left:
        case Button::right:
            return {};
        case Button::back:
            if (enter_after_list_) {
                enter_after_list_ = false;
                begin_entry(model);
                return {};
            }
            mode_ = mode_ == Mode::quit_menu ? Mode::browse : Mode::menu;
            return {};
        case Button::select:
            break;
    }
    const Mode was = mode_;
    mode_ = Mode::browse;
    if (size == 0) {
        return {};
    }
    const auto chosen = static_cast<std::size_t>(list_.index());
    switch (was) {
        case Mode::clef_menu:
            model.set_bar_clef(model.clef_choices()[chosen].id);
            if (enter_after_list_) {
                enter_after_list_ = false;
                begin_entry(model);
            }
            return {};
        case Mode::open_menu:
            last_open_ = list_.index();
            return {Request::Kind::open, (*openable_)[chosen]};
        case Mode::quit_menu:
            if (chosen == 0) {
                return save_under(destination_, true);
            }
            if (chosen == 1) {
                return {Request::Kind::quit};
            }
            return {};
        default:
            return {};
    }
}

Request ButtonScheme::perform(const Command& command, EditorModel& model) {
    const auto& record = record_of(command.action);
    if (record.session != nullptr) {
        return record.session(*this, model);
    }
    model.apply(command);
    return {};
}

void ButtonScheme::open_score_list() {
    if (openable_->empty()) {
        return;
    }
    list_.set(last_open_, static_cast<int>(openable_->size()));
    mode_ = Mode::open_menu;
}

Request ButtonScheme::ask_quit(const EditorModel& model) {
    if (!model.modified()) {
        return {Request::Kind::quit};
    }
    list_.set(0, 3);
    mode_ = Mode::quit_menu;
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

Request ButtonScheme::use_for_press(Button button, EditorModel& model) {
    const int size = static_cast<int>(events_->size()) + 1;
    if (!choosing(button, size, Mode::browse)) {
        return {};
    }
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

const ClefEditor* ButtonScheme::clef_editor() const {
    const bool open =
        mode_ == Mode::clef_edit || mode_ == Mode::clef_name || mode_ == Mode::clef_close;
    return open ? &clef_editor_ : nullptr;
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

Request ButtonScheme::clef_list_press(Button button, EditorModel&) {
    const int size = static_cast<int>(clef_book_->clefs().size());
    if (!choosing(button, size, Mode::menu)) {
        return {};
    }
    const auto& chosen = clef_book_->clefs()[static_cast<std::size_t>(list_.index())];
    clef_editor_ = ClefEditor(chosen.declaration.id, chosen.clef);
    mode_ = Mode::clef_edit;
    return {};
}

namespace {

Request hearing(const ClefEditor& editor) {
    Request request{Request::Kind::hear_clef, editor.id()};
    request.document = write_clef(editor.clef());
    request.string = editor.string();
    request.number = editor.number();
    return request;
}

}  // namespace

Request ButtonScheme::clef_edit_press(Button button) {
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

Request ButtonScheme::clef_name_press(Button button) {
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

Request ButtonScheme::clef_close_press(Button button) {
    if (!choosing(button, 3, Mode::clef_edit)) {
        return {};
    }
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

Request ButtonScheme::assigned_press(Button button, EditorModel& model) {
    if (!choosing(button, 2, Mode::browse)) {
        return {};
    }
    mode_ = Mode::browse;
    if (list_.index() == 0) {
        // Said after the question closes, by the event's own name (the one fbcli and the theme
        // use), so the line confirms what was done.
        model.say(assigned_before_.event + " plays " + assigned_score_);
    } else {
        return {Request::Kind::keep_event, score_before(assigned_before_), 0, false,
                assigned_before_.event};
    }
    return {};
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

Request ButtonScheme::name_press(Button button) {
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

Request ButtonScheme::replace_press(Button button, const EditorModel& model) {
    if (!choosing(button, kReplaceChoices, Mode::browse)) {
        return {};
    }
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

void ButtonScheme::leave_layers(EditorModel& model) {
    if (mode_ == Mode::entry) {
        model.cancel_entry();
    }
    mode_ = Mode::browse;
    enter_after_list_ = false;
    taps_ = {};
}

Request ButtonScheme::command(const Command& command, EditorModel& model) {
    if (mode_ == Mode::playing) {
        return {Request::Kind::stop};
    }
    if (typing_a_name()) {
        // A letter's action would leave the name half typed (at 80x24 every letter is one).
        model.say(kOnlyNameCharacters);
        return {};
    }
    if (mode_ == Mode::clef_list || clef_editor() != nullptr) {
        // A letter key at 80x24 would otherwise drop the clef being edited without a word.
        model.say("a clef is open: Back, Back closes it");
        return {};
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
    MenuView view;
    switch (mode_) {
        case Mode::menu: {
            const auto entries = main_menu(model);
            for (const auto& entry : entries) {
                view.lines.push_back(entry.label);
            }
            view.highlighted = main_.index();
            const MenuGroup group = entries[static_cast<std::size_t>(view.highlighted)].group;
            view.title = "menu: " + std::string(group_name(group)) + " " +
                         std::to_string(static_cast<int>(group) + 1) + "/" +
                         std::to_string(menu_group_count);
        } break;
        case Mode::clef_menu:
            view.title = "clef of bar " + std::to_string(model.cursor().bar + 1);
            for (const auto& clef : model.clef_choices()) {
                view.lines.push_back(clef.id + "  " + clef.href);
            }
            view.highlighted = list_.index();
            break;
        case Mode::open_menu:
            view.title = "open";
            view.lines = *openable_;
            view.highlighted = list_.index();
            break;
        case Mode::quit_menu:
            view.title = "unsaved changes";
            view.lines.assign(std::begin(kQuitChoices), std::end(kQuitChoices));
            view.highlighted = list_.index();
            break;
        case Mode::name_entry:
            view.title = "save as";
            view.lines = name_.lines();
            view.highlighted = name_.highlighted();
            break;
        case Mode::clef_list:
            view.title = "edit clefs";
            for (const auto& known : clef_book_->clefs()) {
                char tempo[32];
                std::snprintf(tempo, sizeof tempo, "%.2f s", known.clef.tempo);
                view.lines.push_back(known.declaration.id + "  " +
                                     std::string(to_string(known.clef.type)) + " " + tempo);
            }
            view.highlighted = list_.index();
            break;
        case Mode::clef_name:
            view.title = "save clef as";
            view.lines = name_.lines();
            view.highlighted = name_.highlighted();
            break;
        case Mode::clef_close:
            view.title = clef_editor_.id() + " changed";
            view.lines = {"save as...", "drop the changes", "cancel"};
            view.highlighted = list_.index();
            break;
        case Mode::use_for:
            view.title = assign_only_ ? "use " + destination_ + " for" : "use for ...";
            for (const auto& event : *events_) {
                view.lines.push_back(event_label(event.event) + ": " +
                                     (event.score.empty() ? "-" : event.score));
            }
            view.lines.push_back(assign_only_       ? "no event"
                                 : pending_save_as_ ? "no event: a name..."
                                                    : "no event: just save");
            view.highlighted = list_.index();
            break;
        case Mode::no_events: {
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
        } break;
        case Mode::assigned:
            // Narrow screens: the title holds the event, the lines the two scores.
            view.title = event_label(assigned_before_.event) + " plays:";
            view.lines = {
                assigned_score_ + " (ok)",
                "keep as it was (" +
                    (assigned_before_.score.empty() ? std::string("-") : assigned_before_.score) +
                    ")"};
            view.highlighted = list_.index();
            break;
        case Mode::replace_menu:
            view.title = replace_title(replacing_);
            view.lines = {"save as another name", replace_choice(replacing_), "cancel"};
            view.highlighted = list_.index();
            break;
        default:
            break;
    }
    return view;
}

std::string ButtonScheme::hint(const EditorModel& model) const {
    // Short enough to share a 40-column status line with what is being entered.
    switch (mode_) {
        case Mode::browse:
            return browse_hint(model);
        case Mode::browse_choices:
            return "\u2191play all \u2193play bar \u2190first \u2192last S:menu";
        case Mode::entry:
            return steps_.hint(model);
        case Mode::menu:
            return "\u2191\u2193choose \u2190\u2192group Sel:ok Back:close";
        case Mode::clef_menu:
        case Mode::open_menu:
        case Mode::quit_menu:
            return "\u2191\u2193choose  Sel:ok  Back:close";
        case Mode::name_entry:
            return name_.hint();
        case Mode::replace_menu:
            return replace_hint(replacing_);
        case Mode::tapping: {
            // Counted as they come, so a person sees each tap taken.
            const int tapped = taps_.taps();
            const std::string count = tapped == 0   ? "tap"
                                      : tapped == 1 ? "1 tap"
                                                    : std::to_string(tapped) + " taps";
            return count + " S:note \u2193rest \u2191 B:done \u2190drop";
        }
        case Mode::use_for:
            return assign_only_ ? "\u2191\u2193choose Sel:use for it Back:close"
                                : "\u2191\u2193choose Sel:save for it Back:close";
        case Mode::no_events:
            return "Sel/Back:close";
        case Mode::clef_list:
            return "\u2191\u2193choose Sel:edit Back:close";
        case Mode::clef_edit:
            return clef_editor_.hint();
        case Mode::clef_name:
            return name_.hint();
        case Mode::clef_close:
            return "\u2191\u2193choose Sel:ok";
        case Mode::assigned:
            return "\u2191\u2193choose Sel:ok";
        case Mode::playing:
            return "playing: any button stops";
    }
    return {};
}

}  // namespace vibscore::editor
