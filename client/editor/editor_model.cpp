#include "client/editor/editor_model.hpp"

#include <algorithm>
#include <set>

#include "client/editor/recurrence.hpp"

namespace vibscore::editor {

namespace {

// The registry's proposal is taken only when at least this many symbols (the score's start
// counting as one) lead to it as they led to it in a registry score.
constexpr int kShortestLearnedPhrase = 2;

std::set<std::string> clefs_in_use(const Score& score) {
    std::set<std::string> ids;
    for (const auto& bar : score.bars) {
        ids.insert(bar.clef);
    }
    return ids;
}

// Removes the declarations of clefs the edit took the last bars from; others stay as read.
void drop_clefs_no_longer_used(Score& score, const std::set<std::string>& used_before) {
    const auto used_now = clefs_in_use(score);
    std::erase_if(score.clefs, [&](const ClefDeclaration& clef) {
        return used_before.contains(clef.id) && !used_now.contains(clef.id);
    });
}

}  // namespace

EditorModel::EditorModel(Score score, std::vector<ClefDeclaration> available_clefs)
    : score_(std::move(score)), saved_(score_), available_clefs_(std::move(available_clefs)) {
    if (score_->bars.empty()) {
        // The editor needs a bar to stand in; a score with none gets one with its first clef.
        auto fresh = score_.copy();
        const auto& available = *available_clefs_;
        const std::string clef = !fresh->clefs.empty() ? fresh->clefs.front().id
                                 : !available.empty()  ? available.front().id
                                                       : std::string();
        if (fresh->clefs.empty() && !available.empty()) {
            fresh->clefs.push_back(available.front());
        }
        fresh->bars.push_back(Bar{clef, {}});
        score_ = fresh;
        saved_ = score_;
    }
    land();
    message_.clear();
}

Score EditorModel::blank_score(std::string title, const ClefDeclaration& clef) {
    Score score;
    score.title = std::move(title);
    score.clefs.push_back(clef);
    score.bars.push_back(Bar{clef.id, {}});
    return score;
}

void EditorModel::add_available_clef(const ClefDeclaration& clef) {
    auto clefs = *available_clefs_;
    if (std::find(clefs.begin(), clefs.end(), clef) == clefs.end()) {
        clefs.push_back(clef);
        available_clefs_ = std::move(clefs);
    }
}

void EditorModel::set_title(std::string title) {
    if (title != score_->title) {
        edit().title = std::move(title);
    }
}

std::vector<ClefDeclaration> EditorModel::clef_choices() const {
    std::vector<ClefDeclaration> choices = score_->clefs;
    for (const auto& clef : *available_clefs_) {
        const bool declared = std::any_of(choices.begin(), choices.end(), [&](const auto& c) {
            return c.id == clef.id || c.href == clef.href;
        });
        if (!declared) {
            choices.push_back(clef);
        }
    }
    return choices;
}

std::optional<Block> EditorModel::block() const {
    if (!anchor_) {
        return std::nullopt;
    }
    const Position first = std::min(*anchor_, cursor_);
    Position last = std::max(*anchor_, cursor_);
    if (anchor_sticky_ && symbol_at(*score_, last) != nullptr) {
        // Marked from the menu, both ends are symbols the user stood on: the block holds them,
        // so a bar marked from its first symbol to its last is the whole bar.
        ++last.symbol;
    }
    if (first == last) {
        return std::nullopt;
    }
    return Block{first, last};
}

Symbol EditorModel::proposed_symbol() const {
    if (const auto recurring = recurrence_at(*score_, cursor_)) {
        if (recurring->pitch_known || std::holds_alternative<Rest>(recurring->next)) {
            return recurring->next;
        }
        Note note = proposed_note();  // the rhythm that recurs, on the note the rules propose
        note.length = length_of(recurring->next);
        return note;
    }
    if (phrases_) {
        // A phrase of one symbol (or the start alone) says too little: on the notification set
        // following it cost more presses than the rules of proposed_note() (docs/performance.md).
        const auto learned = phrases_->next_after(*score_, cursor_);
        if (learned && learned->context >= kShortestLearnedPhrase) {
            return learned->next;
        }
    }
    return proposed_note();
}

Note EditorModel::proposed_note() const {
    Note note;
    note.length = length_;
    note.number = number_;
    note.string = string_;
    // Strength marks belong to each note (its own swell or fade), so they carry over rests as
    // the number and length do; ties and fades join neighbours, which a rest parts.
    for (auto at = symbol_before(*score_, cursor_); at; at = symbol_before(*score_, *at)) {
        if (const Note* last = note_at(*score_, *at)) {
            note.dynamics = last->dynamics;
            break;
        }
    }
    const auto before = symbol_before(*score_, cursor_);
    if (const Note* previous = before ? note_at(*score_, *before) : nullptr) {
        note.legato = previous->legato;
        note.portamento = previous->portamento;
        // A strength that stepped from the note before keeps stepping: fades and swells are
        // runs of notes a step apart.
        const auto two_before = symbol_before(*score_, *before);
        if (const Note* earlier = two_before ? note_at(*score_, *two_before) : nullptr) {
            note.number =
                std::clamp(2 * previous->number - earlier->number, lowest_number, highest_number);
        }
    }
    return note;
}

std::optional<Position> EditorModel::at_hand() const {
    if (!is_empty_position(*score_, cursor_)) {
        return cursor_;
    }
    return symbol_before(*score_, cursor_);
}

std::vector<Position> EditorModel::targets() const {
    if (const auto marked = block()) {
        std::vector<Position> found;
        for (const auto at : symbols_in(*score_, *marked)) {
            if (!std::holds_alternative<Blank>(*symbol_at(*score_, at))) {
                found.push_back(at);
            }
        }
        return found;
    }
    if (const auto at = at_hand()) {
        return {*at};
    }
    return {};
}

std::vector<Position> EditorModel::target_notes() const {
    std::vector<Position> notes;
    for (const auto at : targets()) {
        if (note_at(*score_, at) != nullptr) {
            notes.push_back(at);
        }
    }
    return notes;
}

Snapshot EditorModel::snapshot() const {
    return {score_, cursor_, string_};
}

Score& EditorModel::edit() {
    if (!in_entry_) {
        history_.record(snapshot());
    }
    auto copy = score_.copy();
    Score& score = *copy;
    score_ = std::move(copy);
    return score;
}

void EditorModel::restore(const Snapshot& snapshot) {
    score_ = snapshot.score;
    cursor_ = snapshot.cursor;
    string_ = snapshot.string;
    anchor_.reset();
    in_entry_ = false;
    entry_proposed_ = false;
    land();
}

void EditorModel::land() {
    const auto& bars = score_->bars;
    cursor_.bar = std::min(cursor_.bar, bars.size() - 1);
    cursor_.symbol = std::min(cursor_.symbol, bars[cursor_.bar].symbols.size());
    if (const Note* note = note_at(*score_, cursor_)) {
        string_ = note->string;
    }
}

bool EditorModel::refuse(std::string why) {
    message_ = std::move(why);
    return false;
}

bool EditorModel::done(std::string what) {
    message_ = std::move(what);
    return true;
}

// --- moving -------------------------------------------------------------------------------

void EditorModel::step_left() {
    if (cursor_.symbol > 0) {
        --cursor_.symbol;
    } else if (cursor_.bar > 0) {
        --cursor_.bar;
        cursor_.symbol = score_->bars[cursor_.bar].symbols.size();
    }
    land();
}

bool EditorModel::step_right() {
    const auto& bars = score_->bars;
    if (cursor_.symbol < bars[cursor_.bar].symbols.size()) {
        ++cursor_.symbol;
    } else if (cursor_.bar + 1 < bars.size()) {
        ++cursor_.bar;
        cursor_.symbol = 0;
    } else {
        return false;
    }
    land();
    return true;
}

void EditorModel::move_left() {
    if (anchor_ && !anchor_sticky_) {
        anchor_.reset();
    }
    message_.clear();
    step_left();
}

void EditorModel::move_right() {
    if (anchor_ && !anchor_sticky_) {
        anchor_.reset();
    }
    message_.clear();
    if (!step_right() && !anchor_ && !score_->bars[cursor_.bar].symbols.empty()) {
        split_bar();  // past the end of the score: a new bar, as a bar line is the way on
    }
}

void EditorModel::to_first_bar() {
    jump_to({0, 0});
}

void EditorModel::to_last_bar() {
    jump_to({score_->bars.size() - 1, score_->bars.back().symbols.size()});
}

void EditorModel::jump_to(Position position) {
    if (anchor_ && !anchor_sticky_) {
        anchor_.reset();
    }
    message_.clear();
    cursor_ = position;
    land();
}

// The active string wraps around: from the highest string Up goes to the lowest, so any
// string is at most three presses away.
void EditorModel::move_up() {
    string_ = wrapped(string_, +1, lowest_string, highest_string);
    message_.clear();
}

void EditorModel::move_down() {
    string_ = wrapped(string_, -1, lowest_string, highest_string);
    message_.clear();
}

void EditorModel::extend(int direction) {
    if (!anchor_) {
        anchor_ = cursor_;
        anchor_sticky_ = false;
    }
    message_.clear();
    if (direction < 0) {
        step_left();
    } else {
        step_right();
    }
}

void EditorModel::mark_block() {
    anchor_ = cursor_;
    anchor_sticky_ = true;
    message_ = "block marked here: move to its other end";
}

void EditorModel::clear_block() {
    anchor_.reset();
    message_.clear();
}

// --- entering -----------------------------------------------------------------------------

bool EditorModel::insert_note(int number) {
    if (number < lowest_number || number > highest_number) {
        return refuse("numbers are 1 to 9");
    }
    anchor_.reset();
    Note note;
    note.length = length_;
    note.number = number;
    note.string = string_;
    number_ = number;
    insert_symbol(edit(), cursor_, note);
    ++cursor_.symbol;
    land();
    return done("");
}

bool EditorModel::insert_rest() {
    anchor_.reset();
    insert_symbol(edit(), cursor_, Rest{length_});
    ++cursor_.symbol;
    land();
    return done("");
}

bool EditorModel::insert_blank() {
    anchor_.reset();
    auto& symbols = edit().bars[cursor_.bar].symbols;
    symbols.insert(symbols.begin() + static_cast<std::ptrdiff_t>(cursor_.symbol), Blank{});
    return done("");
}

bool EditorModel::begin_entry(Continuing continuing) {
    if (in_entry_) {
        return true;
    }
    anchor_.reset();
    history_.record(snapshot());
    in_entry_ = true;
    if (continuing == Continuing::yes && at_end_of_full_bar()) {
        // Entering runs on into the next bar as a bar fills, as in notation editors: a new one
        // (on the same clef) after the last bar. Leaving takes a new bar back with the proposal.
        if (cursor_.bar + 1 == score_->bars.size()) {
            split_bar_at(edit(), cursor_);
        }
        cursor_ = {cursor_.bar + 1, 0};
    }
    entry_proposed_ = is_empty_position(*score_, cursor_);
    if (entry_proposed_) {
        insert_symbol(edit(), cursor_, proposed_symbol());
        if (const Note* proposed = note_at(*score_, cursor_)) {
            const Note note = *proposed;  // edit() below may copy the score
            for (const Tie tie : {Tie::legato, Tie::portamento}) {
                if (serial(note, tie) != 0) {
                    tie_to_previous(edit(), cursor_, tie);  // a new tie takes the note before
                }
            }
        }
    }
    message_.clear();
    return true;
}

EditorModel::Unlike EditorModel::unlike_last_entered() const {
    if (!in_entry_) {
        return {};
    }
    if (const Note* note = note_at(*score_, cursor_)) {
        return {note->length != length_, note->string != string_};
    }
    if (const auto* rest = std::get_if<Rest>(symbol_at(*score_, cursor_))) {
        return {rest_length_ && rest->length != *rest_length_, false};
    }
    return {};
}

bool EditorModel::at_end_of_full_bar() const {
    const Bar& bar = score_->bars[cursor_.bar];
    return cursor_.symbol == bar.symbols.size() && Score::beat_count(bar) >= beats_in_a_full_bar;
}

void EditorModel::entry_string(int delta) {
    const Symbol* symbol = in_entry_ ? symbol_at(*score_, cursor_) : nullptr;
    if (symbol == nullptr || std::holds_alternative<Blank>(*symbol)) {
        return;
    }
    if (const auto* rest = std::get_if<Rest>(symbol)) {
        Note note = proposed_note();
        note.length = rest->length;
        note.string = wrapped(string_, delta, lowest_string, highest_string);
        string_ = note.string;
        *symbol_at(edit(), cursor_) = note;
        return;
    }
    const Note& note = *std::get_if<Note>(symbol);
    string_ = wrapped(note.string, delta, lowest_string, highest_string);
    if (string_ != note.string) {
        note_at(edit(), cursor_)->string = string_;
    }
}

void EditorModel::entry_number(int delta) {
    const Note* note = in_entry_ ? note_at(*score_, cursor_) : nullptr;
    if (note == nullptr) {
        return;
    }
    number_ = wrapped(note->number, delta, lowest_number, highest_number);
    if (number_ != note->number) {
        note_at(edit(), cursor_)->number = number_;
    }
}

void EditorModel::entry_length(int delta) {
    const Symbol* symbol = in_entry_ ? symbol_at(*score_, cursor_) : nullptr;
    if (symbol == nullptr || std::holds_alternative<Blank>(*symbol)) {
        return;
    }
    const Length now = length_of(*symbol);
    const Length next = stepped(now, delta);
    remember_length(*symbol, next);
    if (next != now) {
        set_length_of(*symbol_at(edit(), cursor_), next);
    }
}

void EditorModel::remember_length(const Symbol& entered, Length length) {
    if (std::holds_alternative<Rest>(entered)) {
        rest_length_ = length;
    } else {
        length_ = length;
    }
}

void EditorModel::entry_rest() {
    const Symbol* symbol = in_entry_ ? symbol_at(*score_, cursor_) : nullptr;
    if (symbol == nullptr || std::holds_alternative<Blank>(*symbol)) {
        return;
    }
    const Length length = rest_length_.value_or(length_);
    if (const auto* rest = std::get_if<Rest>(symbol); rest == nullptr || rest->length != length) {
        *symbol_at(edit(), cursor_) = Rest{length};
    }
    rest_length_ = length;
}

void EditorModel::entry_toggle_dot() {
    const Symbol* symbol = in_entry_ ? symbol_at(*score_, cursor_) : nullptr;
    if (symbol == nullptr || std::holds_alternative<Blank>(*symbol)) {
        return;
    }
    const auto toggled = toggled_dot(length_of(*symbol));
    if (!toggled) {
        refuse("whole notes and 32nd notes have no dotted form");
        return;
    }
    remember_length(*symbol, *toggled);
    set_length_of(*symbol_at(edit(), cursor_), *toggled);
}

void EditorModel::entry_dynamics(Dynamics dynamics) {
    const Note* note = in_entry_ ? note_at(*score_, cursor_) : nullptr;
    if (note != nullptr) {
        set_dynamics(note->dynamics == dynamics ? Dynamics::none : dynamics);
    }
}

void EditorModel::entry_tie(Tie tie) {
    const Note* note = in_entry_ ? note_at(*score_, cursor_) : nullptr;
    if (note == nullptr) {
        return;
    }
    const auto before = symbol_before(*score_, cursor_);
    const Note* previous = before ? note_at(*score_, *before) : nullptr;
    const auto serial_here = serial(*note, tie);
    if (previous != nullptr && serial_here != 0 && serial(*previous, tie) == serial_here) {
        untie(tie);
    } else {
        this->tie(tie);
    }
}

void EditorModel::end_entry() {
    if (!in_entry_) {
        return;
    }
    in_entry_ = false;
    entry_proposed_ = false;
    if (const Snapshot* before = history_.last(); before && *before->score == *score_) {
        history_.drop_last();  // opened and closed without a change
    }
    // What was entered, kept as proposed or not, is what the next proposal starts from.
    if (const Note* note = note_at(*score_, cursor_)) {
        string_ = note->string;
        number_ = note->number;
        length_ = note->length;
    } else if (const auto* rest = std::get_if<Rest>(symbol_at(*score_, cursor_))) {
        rest_length_ = rest->length;
    }
    ++cursor_.symbol;
    land();
}

void EditorModel::cancel_entry() {
    if (!in_entry_) {
        return;
    }
    const Snapshot before = *history_.last();
    history_.drop_last();
    restore(before);
    message_.clear();
}

// --- bars and deleting --------------------------------------------------------------------

bool EditorModel::split_bar() {
    anchor_.reset();
    split_bar_at(edit(), cursor_);
    cursor_ = {cursor_.bar + 1, 0};
    land();
    return done("new bar");
}

bool EditorModel::delete_at_cursor() {
    const auto used_before = clefs_in_use(*score_);
    if (const auto marked = block()) {
        Score& score = edit();
        erase_block(score, *marked);
        drop_clefs_no_longer_used(score, used_before);
        cursor_ = marked->first;
        anchor_.reset();
        land();
        return done("block deleted");
    }
    anchor_.reset();
    if (symbol_at(*score_, cursor_) != nullptr) {
        Score& score = edit();
        if (const Note* note = note_at(score, cursor_)) {
            for (const Tie tie : {Tie::legato, Tie::portamento}) {
                const auto before = symbol_before(score, cursor_);
                const auto after = symbol_after(score, cursor_);
                const Note* previous = before ? note_at(score, *before) : nullptr;
                const Note* next = after ? note_at(score, *after) : nullptr;
                const bool inside_run = serial(*note, tie) != 0 && previous && next &&
                                        serial(*previous, tie) == serial(*note, tie) &&
                                        serial(*next, tie) == serial(*note, tie);
                if (!inside_run) {
                    untie_note(score, cursor_, tie);
                }
            }
        }
        auto& symbols = score.bars[cursor_.bar].symbols;
        symbols.erase(symbols.begin() + static_cast<std::ptrdiff_t>(cursor_.symbol));
        land();
        return done("");
    }
    if (cursor_.bar + 1 < score_->bars.size()) {
        Score& score = edit();
        join_with_next(score, cursor_.bar);
        drop_clefs_no_longer_used(score, used_before);
        land();
        return done("bar line removed");
    }
    if (score_->bars.size() > 1 && score_->bars[cursor_.bar].symbols.empty()) {
        Score& score = edit();
        score.bars.erase(score.bars.begin() + static_cast<std::ptrdiff_t>(cursor_.bar));
        drop_clefs_no_longer_used(score, used_before);
        cursor_ = {cursor_.bar - 1, score.bars[cursor_.bar - 1].symbols.size()};
        land();
        return done("empty bar removed");
    }
    return refuse("nothing to delete here");
}

// --- symbol functions ---------------------------------------------------------------------

bool EditorModel::set_dynamics(Dynamics dynamics) {
    const auto notes = target_notes();
    if (notes.empty()) {
        return refuse("no note here");
    }
    Score& score = edit();
    for (const auto at : notes) {
        note_at(score, at)->dynamics = dynamics;
    }
    return done(std::string(to_string(dynamics)));
}

bool EditorModel::tie(Tie tie) {
    const char* name = tie == Tie::legato ? "legato" : "portamento";
    const auto notes = target_notes();
    if (block() && notes.size() >= 2) {
        tie_together(edit(), notes, tie);
        return done(name);
    }
    if (notes.empty()) {
        return refuse("no note here");
    }
    const auto before = symbol_before(*score_, notes.front());
    if (!before || note_at(*score_, *before) == nullptr) {
        return refuse(std::string("no note just before to tie with ") + name);
    }
    Score changed = *score_;
    tie_to_previous(changed, notes.front(), tie);
    if (changed == *score_) {
        return done(std::string("already ") + name);
    }
    edit() = std::move(changed);
    return done(name);
}

bool EditorModel::untie(Tie tie) {
    const auto notes = target_notes();
    const bool tied = std::any_of(notes.begin(), notes.end(), [&](Position at) {
        return serial(*note_at(*score_, at), tie) != 0;
    });
    if (!tied) {
        return refuse(tie == Tie::legato ? "no legato here" : "no portamento here");
    }
    Score& score = edit();
    for (const auto at : notes) {
        untie_note(score, at, tie);
    }
    return done(tie == Tie::legato ? "legato removed" : "portamento removed");
}

bool EditorModel::set_length(Length length) {
    length_ = length;
    const auto marked = block();
    if (!marked) {
        return done("length " + length_words(length));
    }
    const auto symbols = targets();
    Score& score = edit();
    for (const auto at : symbols) {
        set_length_of(*symbol_at(score, at), length);
    }
    return done("block length " + length_words(length));
}

bool EditorModel::set_length_value(int value) {
    if (value < 0 || value >= length_count) {
        return refuse("no such length");
    }
    return set_length(static_cast<Length>(value));
}

bool EditorModel::toggle_dot() {
    const auto symbols = targets();
    if (symbols.empty()) {
        return refuse("nothing here to dot");
    }
    // One way for the whole block: dotted unless every symbol already is.
    const bool undot = std::all_of(symbols.begin(), symbols.end(), [&](Position at) {
        return is_dotted(length_of(*symbol_at(*score_, at)));
    });
    Score changed = *score_;
    for (const auto at : symbols) {
        Symbol& symbol = *symbol_at(changed, at);
        const Length now = length_of(symbol);
        if (is_dotted(now) == undot) {
            if (const auto toggled = toggled_dot(now)) {
                set_length_of(symbol, *toggled);
            }
        }
    }
    if (changed == *score_) {
        return refuse("whole notes and 32nd notes have no dotted form");
    }
    edit() = std::move(changed);
    if (symbols.size() == 1) {
        length_ = length_of(*symbol_at(*score_, symbols.front()));
    }
    return done(undot ? "not dotted" : "dotted");
}

bool EditorModel::shift_strings(int delta) {
    const auto notes = target_notes();
    if (notes.empty()) {
        return refuse("no note here");
    }
    for (const auto at : notes) {
        const int moved = note_at(*score_, at)->string + delta;
        if (moved < lowest_string || moved > highest_string) {
            return refuse(delta > 0 ? "a note is already on the highest string"
                                    : "a note is already on the lowest string");
        }
    }
    Score& score = edit();
    for (const auto at : notes) {
        note_at(score, at)->string += delta;
    }
    land();
    return done(delta > 0 ? "strings up" : "strings down");
}

bool EditorModel::shift_numbers(int delta) {
    const auto notes = target_notes();
    if (notes.empty()) {
        return refuse("no note here");
    }
    for (const auto at : notes) {
        const int changed = note_at(*score_, at)->number + delta;
        if (changed < lowest_number || changed > highest_number) {
            return refuse(delta > 0 ? "a number is already 9" : "a number is already 1");
        }
    }
    Score& score = edit();
    for (const auto at : notes) {
        note_at(score, at)->number += delta;
    }
    if (notes.size() == 1) {
        number_ = note_at(*score_, notes.front())->number;
    }
    return done(delta > 0 ? "numbers +1" : "numbers -1");
}

// --- clipboard, undo, clefs ---------------------------------------------------------------

bool EditorModel::copy() {
    if (const auto marked = block()) {
        clipboard_ = copy_block(*score_, *marked);
        anchor_.reset();  // copied: moving the cursor to where it goes must not grow the block
        return done("block copied: move, then paste");
    }
    const auto at = at_hand();
    if (!at) {
        return refuse("nothing here to copy");
    }
    clipboard_ = copy_block(*score_, Block{*at, {at->bar, at->symbol + 1}});
    clipboard_.whole_bars = false;  // one symbol, even where it fills its bar
    return done("copied");
}

bool EditorModel::cut() {
    if (!block()) {
        const auto at = at_hand();
        if (!at) {
            return refuse("nothing here to cut");
        }
        anchor_ = *at;
        cursor_ = {at->bar, at->symbol + 1};
    }
    clipboard_ = copy_block(*score_, *block());
    delete_at_cursor();
    return done("cut");
}

bool EditorModel::paste() {
    if (clipboard_.empty()) {
        return refuse("nothing copied yet");
    }
    Score& score = edit();
    if (const auto marked = block()) {
        erase_block(score, *marked);
        cursor_ = marked->first;
    }
    anchor_.reset();
    // Whole bars pasted at a bar line are bars again: bar 1 copied to the end of the score is
    // a new last bar, not more beats in the last one.
    const auto& bar = score.bars.at(cursor_.bar);
    const bool at_bar_line =
        !bar.symbols.empty() && (cursor_.symbol == 0 || cursor_.symbol == bar.symbols.size());
    if (clipboard_.whole_bars && at_bar_line) {
        cursor_ = paste_bars(score, cursor_, clipboard_);
        land();
        return done(clipboard_.bars.size() == 1 ? "bar pasted" : "bars pasted");
    }
    cursor_ = paste_clip(score, cursor_, clipboard_);
    land();
    return done("pasted");
}

bool EditorModel::undo() {
    const auto previous = history_.undo(snapshot());
    if (!previous) {
        return refuse("nothing to undo");
    }
    restore(*previous);
    return done("undone");
}

bool EditorModel::redo() {
    const auto next = history_.redo(snapshot());
    if (!next) {
        return refuse("nothing to redo");
    }
    restore(*next);
    return done("redone");
}

bool EditorModel::set_bar_clef(const std::string& id) {
    const auto choices = clef_choices();
    const auto chosen = std::find_if(choices.begin(), choices.end(),
                                     [&](const ClefDeclaration& clef) { return clef.id == id; });
    if (chosen == choices.end()) {
        return refuse("no clef \"" + id + "\"");
    }
    std::size_t first = cursor_.bar;
    std::size_t last = cursor_.bar;
    if (const auto marked = block()) {
        first = marked->first.bar;
        last = marked->end.symbol == 0 && marked->end.bar > first ? marked->end.bar - 1
                                                                  : marked->end.bar;
    }
    return set_clef_of_bars(first, last, *chosen);
}

bool EditorModel::set_clef_of_bars(std::size_t first, std::size_t last,
                                   const ClefDeclaration& clef) {
    const std::string& id = clef.id;
    if (first > last || last >= score_->bars.size()) {
        return refuse("no such bars");
    }
    const auto used_before = clefs_in_use(*score_);
    Score changed = *score_;
    if (changed.find_clef(id) == nullptr) {
        changed.clefs.push_back(clef);
    }
    for (std::size_t b = first; b <= last; ++b) {
        changed.bars[b].clef = id;
    }
    drop_clefs_no_longer_used(changed, used_before);
    if (changed == *score_) {
        return done("clef " + id);
    }
    edit() = std::move(changed);
    return done("clef " + id);
}

bool EditorModel::insert_bars(const std::vector<Bar>& bars) {
    if (bars.empty()) {
        return refuse("no bars to put in");
    }
    anchor_.reset();
    Score& score = edit();
    std::size_t first = cursor_.bar;
    const auto& here = score.bars.at(cursor_.bar);
    if (here.symbols.empty()) {
        score.bars.erase(score.bars.begin() + static_cast<std::ptrdiff_t>(first));
    } else if (cursor_.symbol == here.symbols.size()) {
        first = cursor_.bar + 1;
    } else if (cursor_.symbol > 0) {
        split_bar_at(score, cursor_);
        first = cursor_.bar + 1;
    }
    score.bars.insert(score.bars.begin() + static_cast<std::ptrdiff_t>(first), bars.begin(),
                      bars.end());
    // A clef the bars use that the score does not declare yet (a tapped rhythm's tempo clef) is
    // declared with them, in the same undo step.
    for (const auto& bar : bars) {
        if (score.find_clef(bar.clef) == nullptr) {
            for (const auto& available : *available_clefs_) {
                if (available.id == bar.clef) {
                    score.clefs.push_back(available);
                }
            }
        }
    }
    cursor_ = {first, 0};
    land();
    return true;
}

}  // namespace vibscore::editor
