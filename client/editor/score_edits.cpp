#include "client/editor/score_edits.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>

namespace vibscore::editor {

std::int64_t& serial(Note& note, Tie tie) {
    return tie == Tie::legato ? note.legato : note.portamento;
}

std::int64_t serial(const Note& note, Tie tie) {
    return tie == Tie::legato ? note.legato : note.portamento;
}

bool is_empty_position(const Score& score, Position at) {
    const Symbol* symbol = symbol_at(score, at);
    return symbol == nullptr || std::holds_alternative<Blank>(*symbol);
}

const Symbol* symbol_at(const Score& score, Position at) {
    const auto& symbols = score.bars.at(at.bar).symbols;
    return at.symbol < symbols.size() ? &symbols[at.symbol] : nullptr;
}

Symbol* symbol_at(Score& score, Position at) {
    auto& symbols = score.bars.at(at.bar).symbols;
    return at.symbol < symbols.size() ? &symbols[at.symbol] : nullptr;
}

Note* note_at(Score& score, Position at) {
    Symbol* symbol = symbol_at(score, at);
    return symbol == nullptr ? nullptr : std::get_if<Note>(symbol);
}

const Note* note_at(const Score& score, Position at) {
    const Symbol* symbol = symbol_at(score, at);
    return symbol == nullptr ? nullptr : std::get_if<Note>(symbol);
}

std::optional<Position> symbol_before(const Score& score, Position at) {
    Position p = at;
    while (true) {
        if (p.symbol == 0) {
            if (p.bar == 0) {
                return std::nullopt;
            }
            --p.bar;
            p.symbol = score.bars[p.bar].symbols.size();
            continue;
        }
        --p.symbol;
        if (!std::holds_alternative<Blank>(score.bars[p.bar].symbols[p.symbol])) {
            return p;
        }
    }
}

std::optional<Position> symbol_after(const Score& score, Position at) {
    Position p = at;
    while (true) {
        ++p.symbol;
        while (p.symbol >= score.bars[p.bar].symbols.size()) {
            if (p.bar + 1 >= score.bars.size()) {
                return std::nullopt;
            }
            ++p.bar;
            p.symbol = 0;
        }
        if (!std::holds_alternative<Blank>(score.bars[p.bar].symbols[p.symbol])) {
            return p;
        }
    }
}

std::vector<Position> symbols_in(const Score& score, const Block& block) {
    std::vector<Position> found;
    for (std::size_t b = block.first.bar; b <= block.end.bar && b < score.bars.size(); ++b) {
        const std::size_t from = b == block.first.bar ? block.first.symbol : 0;
        const std::size_t to = b == block.end.bar ? block.end.symbol : score.bars[b].symbols.size();
        for (std::size_t s = from; s < to && s < score.bars[b].symbols.size(); ++s) {
            found.push_back({b, s});
        }
    }
    return found;
}

std::int64_t unused_serial(const Score& score, Tie tie) {
    std::int64_t largest = 0;
    for (const auto& bar : score.bars) {
        for (const auto& symbol : bar.symbols) {
            if (const auto* note = std::get_if<Note>(&symbol)) {
                largest = std::max(largest, serial(*note, tie));
            }
        }
    }
    return largest + 1;
}

namespace {

// Gives every note of the run tied with `old_serial` that starts at `from` the serial `value`.
void retie_run(Score& score, Position from, Tie tie, std::int64_t old_serial, std::int64_t value) {
    std::optional<Position> at = from;
    while (at) {
        Note* note = note_at(score, *at);
        if (note == nullptr || serial(*note, tie) != old_serial) {
            return;
        }
        serial(*note, tie) = value;
        at = symbol_after(score, *at);
    }
}

}  // namespace

bool tie_to_previous(Score& score, Position at, Tie tie) {
    const auto before = symbol_before(score, at);
    Note* note = note_at(score, at);
    if (!before || note == nullptr) {
        return false;
    }
    Note* previous = note_at(score, *before);
    if (previous == nullptr) {
        return false;
    }
    std::int64_t value = serial(*previous, tie);
    if (value == 0) {
        value = serial(*note, tie) != 0 ? serial(*note, tie) : unused_serial(score, tie);
        serial(*previous, tie) = value;
    }
    const std::int64_t old = serial(*note, tie);
    if (old != 0 && old != value) {
        retie_run(score, at, tie, old, value);  // the notes tied after it come along
    }
    serial(*note, tie) = value;
    return true;
}

void tie_together(Score& score, const std::vector<Position>& notes, Tie tie) {
    const std::int64_t value = unused_serial(score, tie);
    for (const auto at : notes) {
        serial(*note_at(score, at), tie) = value;
    }
}

void untie_note(Score& score, Position at, Tie tie) {
    Note* note = note_at(score, at);
    if (note == nullptr || serial(*note, tie) == 0) {
        return;
    }
    const std::int64_t value = serial(*note, tie);
    serial(*note, tie) = 0;
    // A neighbour whose only partner was this note would keep a serial that ties nothing.
    const auto tied_to = [&](std::optional<Position> p) {
        const Note* other = p ? note_at(score, *p) : nullptr;
        return other != nullptr && serial(*other, tie) == value;
    };
    if (const auto before = symbol_before(score, at); tied_to(before)) {
        if (!tied_to(symbol_before(score, *before))) {
            serial(*note_at(score, *before), tie) = 0;
        }
    }
    if (const auto after = symbol_after(score, at); tied_to(after)) {
        if (!tied_to(symbol_after(score, *after))) {
            serial(*note_at(score, *after), tie) = 0;
        }
    }
}

Length length_of(const Symbol& symbol) {
    if (const auto* note = std::get_if<Note>(&symbol)) {
        return note->length;
    }
    if (const auto* rest = std::get_if<Rest>(&symbol)) {
        return rest->length;
    }
    return Length::quarter;
}

void set_length_of(Symbol& symbol, Length length) {
    if (auto* note = std::get_if<Note>(&symbol)) {
        note->length = length;
    } else if (auto* rest = std::get_if<Rest>(&symbol)) {
        rest->length = length;
    }
}

void insert_symbol(Score& score, Position at, Symbol symbol) {
    auto& symbols = score.bars.at(at.bar).symbols;
    if (at.symbol < symbols.size() && std::holds_alternative<Blank>(symbols[at.symbol])) {
        symbols[at.symbol] = std::move(symbol);
        return;
    }
    symbols.insert(symbols.begin() + static_cast<std::ptrdiff_t>(at.symbol), std::move(symbol));
}

void split_bar_at(Score& score, Position at) {
    auto& bar = score.bars.at(at.bar);
    Bar tail{bar.clef, {}};
    const auto cut = bar.symbols.begin() + static_cast<std::ptrdiff_t>(at.symbol);
    tail.symbols.assign(std::make_move_iterator(cut), std::make_move_iterator(bar.symbols.end()));
    bar.symbols.erase(cut, bar.symbols.end());
    score.bars.insert(score.bars.begin() + static_cast<std::ptrdiff_t>(at.bar) + 1,
                      std::move(tail));
}

void join_with_next(Score& score, std::size_t bar) {
    auto next = std::move(score.bars.at(bar + 1).symbols);
    auto& symbols = score.bars[bar].symbols;
    symbols.insert(symbols.end(), std::make_move_iterator(next.begin()),
                   std::make_move_iterator(next.end()));
    score.bars.erase(score.bars.begin() + static_cast<std::ptrdiff_t>(bar) + 1);
}

void erase_block(Score& score, const Block& block) {
    if (block.first >= block.end) {
        return;
    }
    auto& first = score.bars.at(block.first.bar).symbols;
    if (block.first.bar == block.end.bar) {
        first.erase(first.begin() + static_cast<std::ptrdiff_t>(block.first.symbol),
                    first.begin() + static_cast<std::ptrdiff_t>(block.end.symbol));
        return;
    }
    auto& last = score.bars.at(block.end.bar).symbols;
    std::vector<Symbol> kept(
        std::make_move_iterator(last.begin() + static_cast<std::ptrdiff_t>(block.end.symbol)),
        std::make_move_iterator(last.end()));
    first.erase(first.begin() + static_cast<std::ptrdiff_t>(block.first.symbol), first.end());
    first.insert(first.end(), std::make_move_iterator(kept.begin()),
                 std::make_move_iterator(kept.end()));
    score.bars.erase(score.bars.begin() + static_cast<std::ptrdiff_t>(block.first.bar) + 1,
                     score.bars.begin() + static_cast<std::ptrdiff_t>(block.end.bar) + 1);
}

bool Clip::empty() const {
    return std::all_of(bars.begin(), bars.end(),
                       [](const Bar& bar) { return bar.symbols.empty(); }) &&
           bars.size() <= 1;
}

Clip copy_block(const Score& score, const Block& block) {
    Clip clip;
    if (block.first >= block.end) {
        return clip;
    }
    for (std::size_t b = block.first.bar; b <= block.end.bar; ++b) {
        const auto& bar = score.bars.at(b);
        const std::size_t from = b == block.first.bar ? block.first.symbol : 0;
        const std::size_t to = b == block.end.bar ? block.end.symbol : bar.symbols.size();
        Bar part{bar.clef, {}};
        part.symbols.assign(bar.symbols.begin() + static_cast<std::ptrdiff_t>(from),
                            bar.symbols.begin() + static_cast<std::ptrdiff_t>(to));
        clip.bars.push_back(std::move(part));
    }
    // Whole bars: from a bar's first symbol to the end of a bar, or to the start of the next
    // (the bar line, which bars have anyway).
    if (block.first.symbol == 0 && block.end.symbol == 0 && clip.bars.size() > 1 &&
        clip.bars.back().symbols.empty()) {
        clip.bars.pop_back();
        clip.whole_bars = true;
    } else {
        clip.whole_bars = block.first.symbol == 0 &&
                          block.end.symbol == score.bars.at(block.end.bar).symbols.size();
    }
    return clip;
}

namespace {

// The clip as it goes into `score`: ties with fresh serials, so they tie only among
// themselves; clefs the score does not declare replaced by `here_clef`.
Clip fresh_clip(const Score& score, const Clip& clip, const std::string& here_clef) {
    Clip fresh = clip;
    for (const Tie tie : {Tie::legato, Tie::portamento}) {
        std::map<std::int64_t, std::int64_t> renamed;
        std::int64_t next = unused_serial(score, tie);
        for (auto& bar : fresh.bars) {
            for (auto& symbol : bar.symbols) {
                if (auto* note = std::get_if<Note>(&symbol); note && serial(*note, tie) != 0) {
                    auto [entry, added] = renamed.try_emplace(serial(*note, tie), next);
                    next += added ? 1 : 0;
                    serial(*note, tie) = entry->second;
                }
            }
        }
    }
    for (auto& bar : fresh.bars) {
        if (score.find_clef(bar.clef) == nullptr) {
            bar.clef = here_clef;  // copied from a score that declared other clefs
        }
    }
    return fresh;
}

}  // namespace

Position paste_bars(Score& score, Position at, const Clip& clip) {
    if (clip.bars.empty()) {
        return at;
    }
    const Clip fresh = fresh_clip(score, clip, score.bars.at(at.bar).clef);
    const std::size_t first = at.symbol == 0 ? at.bar : at.bar + 1;
    score.bars.insert(score.bars.begin() + static_cast<std::ptrdiff_t>(first), fresh.bars.begin(),
                      fresh.bars.end());
    const std::size_t last = first + fresh.bars.size() - 1;
    return {last, score.bars[last].symbols.size()};
}

Position paste_clip(Score& score, Position at, const Clip& clip) {
    if (clip.bars.empty()) {
        return at;
    }
    const Clip fresh = fresh_clip(score, clip, score.bars.at(at.bar).clef);
    split_bar_at(score, at);
    Position end{at.bar, at.symbol};
    for (std::size_t i = 0; i < fresh.bars.size(); ++i) {
        if (i > 0) {
            split_bar_at(score, end);
            score.bars[end.bar + 1].clef = fresh.bars[i].clef;
            end = {end.bar + 1, 0};
        }
        auto& symbols = score.bars[end.bar].symbols;
        symbols.insert(symbols.end(), fresh.bars[i].symbols.begin(), fresh.bars[i].symbols.end());
        end.symbol = symbols.size();
    }
    join_with_next(score, end.bar);  // the symbols that stood after `at`
    return end;
}

namespace {

constexpr Length kPlain[] = {Length::thirty_second, Length::sixteenth, Length::eighth,
                             Length::quarter,       Length::half,      Length::whole};
constexpr Length kDotted[] = {Length::sixteenth_dot, Length::eighth_dot, Length::quarter_dot,
                              Length::half_dot};

template <std::size_t N>
int index_in(const Length (&list)[N], Length length) {
    for (std::size_t i = 0; i < N; ++i) {
        if (list[i] == length) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

}  // namespace

bool is_dotted(Length length) {
    return index_in(kDotted, length) >= 0;
}

std::string length_name(Length length) {
    return length == Length::thirty_second ? "32nd" : std::string(to_string(length));
}

std::string length_words(Length length) {
    std::string name = length_name(length);
    if (name.ends_with("_dot")) {
        return "dotted " + name.substr(0, name.size() - 4);
    }
    return name;
}

Length shorter(Length length) {
    if (const int i = index_in(kPlain, length); i >= 0) {
        return kPlain[std::max(i - 1, 0)];
    }
    const int i = index_in(kDotted, length);
    return i == 0 ? Length::thirty_second : kDotted[i - 1];
}

Length longer(Length length) {
    if (const int i = index_in(kPlain, length); i >= 0) {
        return kPlain[std::min(i + 1, 5)];
    }
    const int i = index_in(kDotted, length);
    return i == 3 ? Length::whole : kDotted[i + 1];
}

Length stepped(Length length, int steps) {
    for (int step = 0; step < std::abs(steps); ++step) {
        length = steps > 0 ? longer(length) : shorter(length);
    }
    return length;
}

int wrapped(int value, int delta, int lowest, int highest) {
    const int span = highest - lowest + 1;
    return lowest + ((value - lowest + delta) % span + span) % span;
}

std::optional<Length> toggled_dot(Length length) {
    switch (length) {
        case Length::half:
            return Length::half_dot;
        case Length::half_dot:
            return Length::half;
        case Length::quarter:
            return Length::quarter_dot;
        case Length::quarter_dot:
            return Length::quarter;
        case Length::eighth:
            return Length::eighth_dot;
        case Length::eighth_dot:
            return Length::eighth;
        case Length::sixteenth:
            return Length::sixteenth_dot;
        case Length::sixteenth_dot:
            return Length::sixteenth;
        case Length::whole:
        case Length::thirty_second:
            break;
    }
    return std::nullopt;
}

}  // namespace vibscore::editor
