#include "client/editor/press_planner.hpp"

#include <deque>
#include <string>
#include <unordered_set>

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

std::string state_key(const Editor& editor) {
    return editor.model.fingerprint() + '@' + editor.scheme.fingerprint();
}

// Two notes agree but for their dynamics and ties: entered, with the marks still to set.
bool same_but_marks(const Token& have, const Token& want) {
    return have.kind == 'N' && want.kind == 'N' && have.length == want.length &&
           have.number == want.number && have.string == want.string;
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

// Progress in eighths of a token, so that each search step is short:
//   8 per bar or symbol entered as the target has it;
//   +5 for a note entered but for its hairpin or ties (set from the menu next);
//   +1..4 while a symbol is being entered on the right string: one for the string, and one
//   each for its number, its length and its shape (note or rest) once they are right.
// -1: the score holds something off the target's path.
constexpr int kUnits = 8;

int progress(const Editor& editor, const Score& target) {
    const auto have = tokens(editor.model.score());
    const auto want = tokens(target);
    std::size_t agree = 0;
    while (agree < have.size() && agree < want.size() && have[agree] == want[agree]) {
        ++agree;
    }
    const int entered = kUnits * static_cast<int>(agree);
    if (agree == have.size()) {
        return entered;
    }
    if (agree + 1 != have.size() || agree >= want.size()) {
        return -1;
    }
    const Token& partial = have[agree];
    const Token& wanted = want[agree];
    if (editor.scheme.mode() == ButtonScheme::Mode::browse) {
        return same_but_marks(partial, wanted) ? entered + 5 : -1;
    }
    if (editor.scheme.mode() != ButtonScheme::Mode::entry || partial.kind == 'b' ||
        wanted.kind == 'b') {
        return -1;
    }
    const bool on_string =
        wanted.kind == 'R' || (partial.kind == 'N' && partial.string == wanted.string);
    if (!on_string) {
        return -1;
    }
    const bool number_right =
        partial.kind == wanted.kind && (wanted.kind == 'R' || partial.number == wanted.number);
    return entered + 1 + (number_right ? 1 : 0) + (partial.length == wanted.length ? 1 : 0) +
           (partial.kind == wanted.kind ? 1 : 0);
}

}  // namespace

PressPlan plan_presses(const Editor& start, const Score& target, std::size_t state_limit) {
    PressPlan plan;
    Editor current = start;
    const int total = kUnits * static_cast<int>(tokens(target).size());
    int reached = std::max(progress(current, target), 0);
    const auto finished = [&](const Editor& editor) {
        return editor.scheme.mode() == ButtonScheme::Mode::browse &&
               same_music(editor.model.score(), target);
    };
    struct Node {
        Editor editor;
        std::vector<Button> presses;
    };
    while (!finished(current)) {
        std::deque<Node> queue;
        std::unordered_set<std::string> seen{state_key(current)};
        queue.push_back({current, {}});
        std::optional<Node> step;
        while (!queue.empty() && !step) {
            Node node = std::move(queue.front());
            queue.pop_front();
            for (const Button button : all_buttons) {
                Node next{node.editor, node.presses};
                if (next.editor.press(button).kind != Request::Kind::none) {
                    continue;  // files, playback and quitting are not entering
                }
                next.presses.push_back(button);
                if (!seen.insert(state_key(next.editor)).second) {
                    continue;
                }
                ++plan.states_seen;
                if (seen.size() > state_limit) {
                    return plan;
                }
                const int now = progress(next.editor, target);
                if (now > reached || (now == total && finished(next.editor))) {
                    reached = now;
                    step = std::move(next);
                    break;
                }
                queue.push_back(std::move(next));
            }
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
