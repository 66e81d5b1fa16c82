#include "client/editor/planner/press_planner.hpp"

#include <algorithm>
#include <deque>
#include <string>
#include <unordered_set>

#include "client/editor/planner/editor_hash.hpp"
#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

namespace {

// A bar line (with its clef) or a symbol, as entering compares them.
struct Token {
    char kind = 'B';  // 'b' bar, 'N' note, 'R' rest, 'B' blank
    std::string clef;
    Length length = Length::quarter;
    int number = 0, string = 0;
    Dynamics dynamics = Dynamics::none;
    // Serials are compared as the ties they make: tied to the note before, or not.
    bool legato_to_previous = false, portamento_to_previous = false;
    bool operator==(const Token&) const = default;
};

std::vector<Token> tokens(const Score& score) {
    std::vector<Token> found;
    const Note* previous = nullptr;  // the note directly before, if the symbol before is one
    for (const auto& bar : score.bars) {
        found.push_back({'b', bar.clef});
        for (const auto& symbol : bar.symbols) {
            if (const auto* note = std::get_if<Note>(&symbol)) {
                Token token{'N'};
                token.length = note->length;
                token.number = note->number;
                token.string = note->string;
                token.dynamics = note->dynamics;
                token.legato_to_previous =
                    previous && note->legato != 0 && note->legato == previous->legato;
                token.portamento_to_previous =
                    previous && note->portamento != 0 && note->portamento == previous->portamento;
                found.push_back(token);
                previous = note;
            } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
                Token token{'R'};
                token.length = rest->length;
                found.push_back(token);
                previous = nullptr;
            } else {
                found.push_back({'B'});
            }
        }
    }
    return found;
}

bool same_music(const Score& a, const Score& b) {
    return a.bars == b.bars && a.clefs == b.clefs;
}

}  // namespace

int entered_prefix(const Score& score, const Score& target) {
    const auto have = tokens(score);
    const auto want = tokens(target);
    std::size_t agree = 0;
    while (agree < have.size() && agree < want.size() && have[agree] == want[agree]) {
        ++agree;
    }
    return agree == have.size() ? static_cast<int>(agree) : -1;
}

namespace {

// Finer progress, for symbols too far from their proposal for a whole-symbol search: eight
// per symbol entered, and one for each thing the symbol being chosen already has right.
constexpr int kUnits = 8;

int fine_progress(const Editor& editor, const Score& target) {
    const int entered = progress(editor, target);
    if (entered < 0 || editor.scheme.mode() != ButtonScheme::Mode::entry) {
        return entered < 0 ? entered : kUnits * entered;
    }
    const auto have = tokens(editor.model.score());
    const auto want = tokens(target);
    const auto at = static_cast<std::size_t>(entered);
    if (at >= have.size() || at >= want.size()) {
        return kUnits * entered;
    }
    const Token& open = have[at];
    const Token& wanted = want[at];
    int right = open.kind == wanted.kind ? 1 : 0;
    right += open.length == wanted.length ? 1 : 0;
    if (open.kind == 'N' && wanted.kind == 'N') {
        right += (open.string == wanted.string ? 1 : 0) + (open.number == wanted.number ? 1 : 0) +
                 (open.dynamics == wanted.dynamics ? 1 : 0) +
                 (open.legato_to_previous == wanted.legato_to_previous &&
                          open.portamento_to_previous == wanted.portamento_to_previous
                      ? 1
                      : 0);
    }
    return kUnits * entered + right;
}

struct Node {
    Editor editor;
    std::vector<Button> presses;
};

bool finished(const Editor& editor, const Score& target) {
    return editor.scheme.mode() == ButtonScheme::Mode::browse &&
           same_music(editor.model.score(), target);
}

// Breadth-first from `from` to the nearest state that `measure` puts further on, or that is
// the finished target. nullopt when there is none within `state_limit` states.
template <typename Measure>
std::optional<Node> next_step(const Editor& from, const Score& target, Measure measure,
                              std::size_t state_limit, std::size_t& states_seen) {
    const int reached = measure(from, target);
    std::deque<Node> queue;
    std::unordered_set<Editor, EditorHash> seen{from};
    queue.push_back({from, {}});
    while (!queue.empty()) {
        Node node = std::move(queue.front());
        queue.pop_front();
        for (const Button button : all_buttons) {
            Node next{node.editor, node.presses};
            if (next.editor.press(button).kind != Request::Kind::none) {
                continue;  // files, playback and quitting are not entering
            }
            next.presses.push_back(button);
            if (!seen.insert(next.editor).second) {
                continue;
            }
            ++states_seen;
            if (seen.size() > state_limit) {
                return std::nullopt;
            }
            if (measure(next.editor, target) > reached || finished(next.editor, target)) {
                return next;
            }
            queue.push_back(std::move(next));
        }
    }
    return std::nullopt;
}

}  // namespace

int progress(const Editor& editor, const Score& target) {
    if (editor.scheme.mode() != ButtonScheme::Mode::entry) {
        return entered_prefix(editor.model.score(), target);
    }
    Score without_open = editor.model.score();
    const Position open = editor.model.cursor();
    auto& symbols = without_open.bars.at(open.bar).symbols;
    if (open.symbol < symbols.size()) {
        symbols.erase(symbols.begin() + static_cast<std::ptrdiff_t>(open.symbol));
    }
    const int entered = entered_prefix(without_open, target);
    if (entered >= 0 || !symbols.empty() || open.bar + 1 != without_open.bars.size()) {
        return entered;
    }
    without_open.bars.pop_back();
    return entered_prefix(without_open, target);
}

namespace {

int agreeing_prefix(const Editor& editor, const Score& target) {
    const auto have = tokens(editor.model.score());
    const auto want = tokens(target);
    int agree = 0;
    while (static_cast<std::size_t>(agree) < have.size() &&
           static_cast<std::size_t>(agree) < want.size() &&
           have[static_cast<std::size_t>(agree)] == want[static_cast<std::size_t>(agree)]) {
        ++agree;
    }
    // Only changes count: a symbol or bar line more or less (a proposal opened past the end,
    // a bar split) is no nearer.
    return have.size() == want.size() ? agree : -1;
}

}  // namespace

PressPlan plan_changes(const Editor& start, const Score& target, std::size_t state_limit) {
    PressPlan plan;
    Editor current = start;
    while (!finished(current, target)) {
        auto step = next_step(current, target, agreeing_prefix, state_limit, plan.states_seen);
        if (!step) {
            return plan;
        }
        current = std::move(step->editor);
        plan.presses.insert(plan.presses.end(), step->presses.begin(), step->presses.end());
    }
    plan.reached = true;
    return plan;
}

PressPlan plan_name(const NameEntry& start, const std::string& name) {
    PressPlan plan;
    struct Step {
        NameEntry entry;
        std::vector<Button> presses;
    };
    const auto on_the_way = [&](const NameEntry& entry) {
        const std::string& now = entry.name();
        if (entry.untouched() || name.starts_with(now)) {
            return true;
        }
        for (const auto& line : start.lines()) {
            if (line.starts_with(now) || line.starts_with("[" + now)) {
                return true;
            }
        }
        return false;
    };
    std::vector<NameEntry> seen{start};
    std::deque<Step> queue{{start, {}}};
    while (!queue.empty()) {
        const Step from = std::move(queue.front());
        queue.pop_front();
        for (const Button button : all_buttons) {
            Step next{from.entry, from.presses};
            const auto outcome = next.entry.press(button);
            next.presses.push_back(button);
            ++plan.states_seen;
            if (outcome == NameEntry::Outcome::done) {
                if (next.entry.name() == name) {
                    plan.presses = std::move(next.presses);
                    plan.reached = true;
                    return plan;
                }
                continue;
            }
            if (outcome == NameEntry::Outcome::cancelled || !on_the_way(next.entry) ||
                std::find(seen.begin(), seen.end(), next.entry) != seen.end()) {
                continue;
            }
            seen.push_back(next.entry);
            queue.push_back(std::move(next));
        }
    }
    return plan;
}

PressPlan plan_presses(const Editor& start, const Score& target, std::size_t state_limit) {
    PressPlan plan;
    Editor current = start;
    // A whole symbol is searched for first; one that lies deeper (a new bar with another
    // clef, a note far from its proposal) is reached through its parts.
    const std::size_t whole_limit = std::min<std::size_t>(state_limit, 200'000);
    while (!finished(current, target)) {
        auto step = next_step(current, target, progress, whole_limit, plan.states_seen);
        if (!step) {
            step = next_step(current, target, fine_progress, state_limit, plan.states_seen);
        }
        if (!step) {
            return plan;
        }
        current = std::move(step->editor);
        plan.presses.insert(plan.presses.end(), step->presses.begin(), step->presses.end());
    }
    plan.reached = true;
    return plan;
}

}  // namespace vibscore::editor
