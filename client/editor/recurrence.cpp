#include "client/editor/recurrence.hpp"

#include <algorithm>

#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

namespace {

constexpr int no_occurrence = 4;

bool same_length(const Symbol& a, const Symbol& b) {
    return a.index() == b.index() && length_of(a) == length_of(b);
}

// The serial that ties a note to `last` as `follower` was tied to `earlier`: `last`'s own, a
// new one when `last` is not tied yet, or none.
std::int64_t tie_like(const Score& score, const Note& follower, const Note& earlier,
                      const Note& last, Tie tie) {
    if (serial(follower, tie) == 0 || serial(follower, tie) != serial(earlier, tie)) {
        return 0;
    }
    return serial(last, tie) != 0 ? serial(last, tie) : unused_serial(score, tie);
}

}  // namespace

std::vector<Placed> placed_before(const Score& score, Position at) {
    std::vector<Placed> found;
    for (std::size_t bar = 0; bar <= at.bar && bar < score.bars.size(); ++bar) {
        const auto& symbols = score.bars[bar].symbols;
        const std::size_t end =
            bar == at.bar ? std::min(at.symbol, symbols.size()) : symbols.size();
        double beat = 0.0;
        for (std::size_t s = 0; s < end; ++s) {
            if (std::holds_alternative<Blank>(symbols[s])) {
                continue;
            }
            found.push_back({&symbols[s], beat});
            beat += beats(length_of(symbols[s]));
        }
    }
    return found;
}

double beat_at(const Score& score, Position at) {
    const auto& symbols = score.bars.at(at.bar).symbols;
    double beat = 0.0;
    for (std::size_t s = 0; s < at.symbol && s < symbols.size(); ++s) {
        if (!std::holds_alternative<Blank>(symbols[s])) {
            beat += beats(length_of(symbols[s]));
        }
    }
    return beat;
}

bool alike(const Symbol& a, const Symbol& b) {
    const auto* note_a = std::get_if<Note>(&a);
    const auto* note_b = std::get_if<Note>(&b);
    if (note_a == nullptr || note_b == nullptr) {
        return same_length(a, b);
    }
    return note_a->string == note_b->string && note_a->number == note_b->number &&
           note_a->length == note_b->length;
}

Note tied_as_before(const Score& score, Note follower, const Note& earlier, const Note& last) {
    const Note as_it_followed = follower;
    follower.legato = tie_like(score, as_it_followed, earlier, last, Tie::legato);
    follower.portamento = tie_like(score, as_it_followed, earlier, last, Tie::portamento);
    return follower;
}

std::optional<Recurrence> recurrence_at(const Score& score, Position at) {
    const auto placed = placed_before(score, at);
    if (placed.size() < 2) {
        return std::nullopt;
    }
    const Placed& last = placed.back();
    // How good an occurrence the earlier symbol is, 0 best (the order in the header).
    const auto rank = [&](const Placed& earlier) {
        const int elsewhere = earlier.beat == last.beat ? 0 : 2;
        if (alike(*earlier.symbol, *last.symbol)) {
            return elsewhere;
        }
        return same_length(*earlier.symbol, *last.symbol) ? elsewhere + 1 : no_occurrence;
    };
    std::size_t best = 0;
    int best_rank = no_occurrence;
    for (std::size_t i = placed.size() - 1; i-- > 0;) {
        if (const int r = rank(placed[i]); r < best_rank) {
            best = i;
            best_rank = r;
        }
    }
    if (best_rank == no_occurrence) {
        return std::nullopt;
    }
    const Symbol& next = *placed[best + 1].symbol;
    const bool same_beat = best_rank < 2;
    const auto* follower = std::get_if<Note>(&next);
    const auto* earlier = std::get_if<Note>(placed[best].symbol);
    const auto* now = std::get_if<Note>(last.symbol);
    if (follower == nullptr || best_rank % 2 == 1 || earlier == nullptr || now == nullptr) {
        return Recurrence{next, false, same_beat};
    }
    return Recurrence{tied_as_before(score, *follower, *earlier, *now), true, same_beat};
}

}  // namespace vibscore::editor
