#include "client/editor/phrase_book.hpp"

#include <algorithm>

#include "client/editor/recurrence.hpp"
#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

namespace {

// Phrases longer than this say nothing more about what comes next, and cost time to compare.
constexpr int kLongestPhrase = 8;

// Symbols alike (recurrence.hpp) share a key.
std::uint64_t alike_key(const Symbol& symbol) {
    const auto length = static_cast<std::uint64_t>(length_of(symbol));
    if (const auto* note = std::get_if<Note>(&symbol)) {
        return (std::uint64_t{1} << 40) | (length << 16) |
               (static_cast<std::uint64_t>(note->string) << 8) |
               static_cast<std::uint64_t>(note->number);
    }
    return (std::uint64_t{2} << 40) | length;
}

// The last note of `symbols` before `end`, over rests; nullptr when there is none.
template <typename Symbols, typename Get>
const Note* last_note_before(const Symbols& symbols, std::size_t end, Get symbol_of) {
    for (std::size_t i = end; i-- > 0;) {
        if (const auto* note = std::get_if<Note>(&symbol_of(symbols[i]))) {
            return note;
        }
    }
    return nullptr;
}

// A learned note as it would follow the last symbol of the score being entered: tied to it as it
// was tied to the note before it where it was learned, untied after a rest. Its hairpin goes on
// as it went on there: where the learned note kept the hairpin of the note before it (over rests
// too), it keeps the hairpin of the score's last note; a hairpin that changed there comes as it
// was learned. (Phrases match by string, number and length, marks aside, so a pulse learned
// with a fade proposes a plain pulse after plain ones.)
Symbol as_follower(const Score& score, const Symbol& learned, const Note* learned_note_before,
                   const Symbol* learned_before, const Note* last_note, const Symbol* last) {
    const auto* note = std::get_if<Note>(&learned);
    if (note == nullptr) {
        return learned;
    }
    Note follower = *note;
    if (learned_note_before != nullptr && last_note != nullptr &&
        follower.dynamics == learned_note_before->dynamics) {
        follower.dynamics = last_note->dynamics;
    }
    const auto* earlier = learned_before ? std::get_if<Note>(learned_before) : nullptr;
    const auto* now = last ? std::get_if<Note>(last) : nullptr;
    if (earlier == nullptr || now == nullptr) {
        follower.legato = 0;
        follower.portamento = 0;
        return follower;
    }
    return tied_as_before(score, follower, *earlier, *now);
}

}  // namespace

void PhraseBook::learn(const Score& score) {
    std::vector<Learned> phrase;
    for (const auto& bar : score.bars) {
        double beat = 0.0;
        for (const auto& symbol : bar.symbols) {
            if (std::holds_alternative<Blank>(symbol)) {
                continue;
            }
            phrase.push_back({symbol, beat});
            beat += beats(length_of(symbol));
        }
    }
    if (phrase.empty()) {
        return;
    }
    const auto number = static_cast<std::uint32_t>(phrases_.size());
    for (std::uint32_t i = 1; i < phrase.size(); ++i) {
        followers_[alike_key(phrase[i - 1].symbol)].push_back({number, i});
    }
    phrases_.push_back(std::move(phrase));
}

std::vector<PhraseBook::Prediction> PhraseBook::candidates(const Score& score, Position at) const {
    const auto context = placed_before(score, at);
    const double beat = beat_at(score, at);
    std::vector<Place> starts;
    const std::vector<Place>* places = &starts;
    if (context.empty()) {
        for (std::uint32_t p = 0; p < phrases_.size(); ++p) {
            starts.push_back({p, 0});
        }
    } else {
        const auto found = followers_.find(alike_key(*context.back().symbol));
        if (found == followers_.end()) {
            return {};
        }
        places = &found->second;
    }
    const Symbol* last = context.empty() ? nullptr : context.back().symbol;
    const Note* last_note = last_note_before(
        context, context.size(), [](const Placed& p) -> const Symbol& { return *p.symbol; });
    std::vector<Prediction> candidates;
    for (const Place& place : *places) {
        const auto& phrase = phrases_[place.phrase];
        int matched = context.empty() ? 0 : 1;
        while (matched < kLongestPhrase && static_cast<std::size_t>(matched) < context.size() &&
               static_cast<std::uint32_t>(matched) < place.index &&
               alike(phrase[place.index - 1 - static_cast<std::uint32_t>(matched)].symbol,
                     *context[context.size() - 1 - static_cast<std::size_t>(matched)].symbol)) {
            ++matched;
        }
        const bool both_start = static_cast<std::uint32_t>(matched) == place.index &&
                                static_cast<std::size_t>(matched) == context.size();
        const int length = matched + (both_start ? 1 : 0);
        const Learned& follower = phrase[place.index];
        const Symbol next = as_follower(
            score, follower.symbol,
            last_note_before(phrase, place.index,
                             [](const Learned& l) -> const Symbol& { return l.symbol; }),
            place.index > 0 ? &phrase[place.index - 1].symbol : nullptr, last_note, last);
        const bool same_beat = follower.beat == beat;
        const auto known = std::find_if(candidates.begin(), candidates.end(),
                                        [&](const Prediction& c) { return c.next == next; });
        if (known == candidates.end()) {
            candidates.push_back({next, length, 1, same_beat});
        } else if (length > known->context) {
            *known = {next, length, 1, same_beat};
        } else if (length == known->context) {
            ++known->occurrences;
            known->same_beat = known->same_beat || same_beat;
        }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Prediction& a, const Prediction& b) {
                         if (a.context != b.context) {
                             return a.context > b.context;
                         }
                         if (a.occurrences != b.occurrences) {
                             return a.occurrences > b.occurrences;
                         }
                         return a.same_beat && !b.same_beat;
                     });
    return candidates;
}

std::optional<PhraseBook::Prediction> PhraseBook::next_after(const Score& score,
                                                             Position at) const {
    auto ranked = candidates(score, at);
    if (ranked.empty() || ranked.front().context == 0) {
        return std::nullopt;
    }
    return std::move(ranked.front());
}

std::shared_ptr<const PhraseBook> learned_from_others(const std::vector<NamedScore>& registry,
                                                      const NamedScore& entering) {
    auto phrases = std::make_shared<PhraseBook>();
    for (const auto& other : registry) {
        if (other.name != entering.name && other.score.bars != entering.score.bars) {
            phrases->learn(other.score);
        }
    }
    return phrases;
}

}  // namespace vibscore::editor
