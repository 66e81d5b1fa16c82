#include "client/formats/score_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include "score/document_error.hpp"
#include "score/limits.hpp"

namespace vibscore::formats {

namespace {

constexpr std::int64_t kTicksPerBar = 4 * ticks_per_quarter;

std::int64_t ticks_of(Length length) {
    return static_cast<std::int64_t>(std::lround(beats(length) * ticks_per_quarter));
}

// A symbol in playing order before it goes into a bar, with the tie to the note after it.
struct Written {
    Symbol symbol;
    std::int64_t ticks = 0;
    GridNote::Tie tie_to_next = GridNote::Tie::none;
};

// Tie serials count up from 1, separately for legato and portamento, as people number them; a
// note tied in one way and out the other carries both serials.
void number_ties(std::vector<Written>& sequence) {
    std::int64_t legato = 0, portamento = 0;
    GridNote::Tie incoming = GridNote::Tie::none;
    for (auto& written : sequence) {
        auto* note = std::get_if<Note>(&written.symbol);
        if (note == nullptr) {
            incoming = GridNote::Tie::none;
            continue;
        }
        if (incoming == GridNote::Tie::legato) {
            note->legato = legato;
        } else if (incoming == GridNote::Tie::portamento) {
            note->portamento = portamento;
        }
        if (written.tie_to_next == GridNote::Tie::legato && incoming != GridNote::Tie::legato) {
            note->legato = ++legato;
        } else if (written.tie_to_next == GridNote::Tie::portamento &&
                   incoming != GridNote::Tie::portamento) {
            note->portamento = ++portamento;
        }
        incoming = written.tie_to_next;
    }
}

// Fills bars of four beats with the sequence: a bar closes early rather than split a note,
// rests split at bar lines, and a new bar begins wherever the tempo changes.
class BarLayout {
  public:
    BarLayout(const std::vector<TempoChange>& tempi, const ChosenClef& chosen)
        : tempi_(tempi), chosen_(chosen) {}

    void add(const Written& written) {
        if (std::holds_alternative<Rest>(written.symbol)) {
            for (std::int64_t left = written.ticks; left > 0;) {
                const std::int64_t take = std::min(left, room());
                for (const Length length : lengths_for(take)) {
                    place(Rest{length}, ticks_of(length));
                }
                left -= take;
            }
            return;
        }
        place(written.symbol, written.ticks);
    }

    std::vector<Bar> bars() && { return std::move(bars_); }
    const std::vector<double>& tempi_used() const { return used_; }

  private:
    bool tempo_changes() const {
        return next_tempo_ < tempi_.size() && tempi_[next_tempo_].at <= now_;
    }
    std::int64_t room() {
        if (bars_.empty() || bar_ticks_ >= kTicksPerBar || tempo_changes()) {
            open_bar();
        }
        return kTicksPerBar - bar_ticks_;
    }
    void open_bar() {
        while (tempo_changes()) {
            tempo_ = tempi_[next_tempo_++].tempo;
        }
        if (std::find(used_.begin(), used_.end(), tempo_) == used_.end()) {
            used_.push_back(tempo_);
        }
        bars_.push_back(Bar{clef_id_for(chosen_, tempo_), {}});
        bar_ticks_ = 0;
    }
    void place(Symbol symbol, std::int64_t ticks) {
        if (bars_.empty() || bar_ticks_ + ticks > kTicksPerBar || tempo_changes()) {
            open_bar();
        }
        bars_.back().symbols.push_back(std::move(symbol));
        bar_ticks_ += ticks;
        now_ += ticks;
    }

    const std::vector<TempoChange>& tempi_;
    const ChosenClef& chosen_;
    std::vector<Bar> bars_;
    std::vector<double> used_;
    std::size_t next_tempo_ = 0;
    double tempo_ = 0.0;
    std::int64_t now_ = 0;
    std::int64_t bar_ticks_ = 0;
};

std::string bpm_label(double tempo) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", 60.0 / tempo);
    std::string label = text;
    label.erase(label.find_last_not_of('0') + 1);
    if (label.back() == '.') {
        label.pop_back();
    }
    return label + "bpm";
}

[[noreturn]] void too_long(const std::string& file, const std::string& what) {
    throw DocumentError({file}, "too long for a score: " + what);
}

std::string bars_limit() {
    return "a score holds at most " + std::to_string(limits::bars) + " bars";
}
std::string symbols_limit() {
    return "a score holds at most " + std::to_string(limits::symbols) + " symbols";
}
std::string seconds_limit() {
    return "a score lasts at most " + seconds_text(limits::max_score_seconds);
}

// The limits the piece's length alone decides, checked before anything is laid
// out: past them the layout would cost time and memory in proportion to the length a file
// claims, which a few bytes of MIDI can make years.
void check_length(const std::vector<GridNote>& notes, const std::vector<TempoChange>& tempi,
                  std::int64_t total_ticks, const std::string& file) {
    std::int64_t end = std::max<std::int64_t>(total_ticks, 0);
    for (const auto& note : notes) {
        end = std::max(end, note.start + std::max<std::int64_t>(note.length, 1));
    }
    if (end > max_import_ticks) {
        too_long(file, "it lasts " + std::to_string(end / ticks_per_quarter) +
                           " beats, more than fit in " + std::to_string(limits::bars) +
                           " bars of four; " + bars_limit());
    }
    const double seconds = seconds_at(tempi, end);
    if (past_the_hour(seconds)) {
        too_long(file, "it lasts " + seconds_text(seconds) + "; " + seconds_limit());
    }
}

// Every limit of a score, on the score as laid out: each message names the one broken.
void check_laid_out(const ImportedScore& imported, const std::string& file) {
    std::size_t symbols = 0;
    double seconds = 0.0;
    for (const auto& bar : imported.score.bars) {
        symbols += bar.symbols.size();
        for (const auto& clef : imported.clefs) {
            if (clef.id == bar.clef) {
                seconds += Score::beat_count(bar) * clef.clef.tempo;
            }
        }
    }
    const auto bars = imported.score.bars.size();
    if (bars > limits::bars) {
        too_long(file, std::to_string(bars) + " bars; " + bars_limit());
    }
    if (symbols > limits::symbols) {
        too_long(file, std::to_string(symbols) + " symbols (notes, tied parts and rests); " +
                           symbols_limit());
    }
    if (past_the_hour(seconds)) {
        too_long(file, "it lasts " + seconds_text(seconds) + "; " + seconds_limit());
    }
    if (imported.clefs.size() > limits::clefs_per_score) {
        throw DocumentError(
            {file}, "too many tempos for a score: " + std::to_string(imported.clefs.size()) +
                        ", each on a clef of its own; a score declares at most " +
                        std::to_string(limits::clefs_per_score) + " clefs");
    }
}

// The levels (0..1 of the clef's strongest number) a note ramps between as the renderer plays
// it: a crescendo from silence or from the crescendo note it directly follows, a decrescendo to
// silence or to the decrescendo note directly after it, a portamento on one string to the next
// note's number. Nothing for a note that holds its level.
std::optional<std::pair<double, double>> ramp_of(const GridNote& note, const GridNote* before,
                                                 const GridNote* after, const Clef& clef) {
    double peak = 0.0;
    for (const double amplitude : clef.numbers) {
        peak = std::max(peak, std::abs(amplitude));
    }
    if (peak <= 0.0) {
        return std::nullopt;
    }
    const auto level = [&](const GridNote& of) {
        return clef.numbers.at(static_cast<std::size_t>(of.number - 1)) / peak;
    };
    switch (note.dynamics) {
        case Dynamics::crescendo:
            return std::make_pair(
                before != nullptr && before->dynamics == Dynamics::crescendo ? level(*before) : 0.0,
                level(note));
        case Dynamics::decrescendo:
            return std::make_pair(
                level(note),
                after != nullptr && after->dynamics == Dynamics::decrescendo ? level(*after) : 0.0);
        case Dynamics::none:
            break;
    }
    if (note.tie_to_next == GridNote::Tie::portamento && after != nullptr &&
        after->string == note.string && after->number != note.number) {
        return std::make_pair(level(note), level(*after));
    }
    return std::nullopt;
}

}  // namespace

void check_document_size(std::string_view text, const std::string& file) {
    if (text.size() > limits::document_bytes) {
        throw DocumentError({file}, "larger than the " + std::to_string(limits::document_bytes) +
                                        "-byte limit for a document");
    }
}

std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, seconds < 1e9 ? "%.3f" : "%.3g", seconds);
    std::string shown = text;
    if (shown.find('.') != std::string::npos && shown.find('e') == std::string::npos) {
        shown.erase(shown.find_last_not_of('0') + 1);
        if (shown.back() == '.') {
            shown.pop_back();
        }
    }
    return shown + " s";
}

bool past_the_hour(double seconds) {
    // As the score reader (score/bundle.cpp): a sum over thousands of bars at a tempo no binary
    // fraction holds, like 0.2 s, builds up rounding; a piece of exactly an hour is a score.
    return seconds > limits::max_score_seconds + 1e-6;
}

double seconds_at(const std::vector<TempoChange>& tempi, std::int64_t tick) {
    double seconds = 0.0;
    for (std::size_t i = 0; i < tempi.size() && tempi[i].at < tick; ++i) {
        const std::int64_t until = i + 1 < tempi.size() ? std::min(tempi[i + 1].at, tick) : tick;
        const double tempo = std::clamp(tempi[i].tempo, limits::min_tempo_s, limits::max_tempo_s);
        seconds += static_cast<double>(until - tempi[i].at) * tempo / ticks_per_quarter;
    }
    return seconds;
}

std::vector<Length> lengths_for(std::int64_t ticks) {
    std::vector<Length> parts;
    for (int i = 0; i < length_count && ticks > 0;) {
        const auto length = static_cast<Length>(i);
        if (ticks_of(length) <= ticks) {
            parts.push_back(length);
            ticks -= ticks_of(length);
        } else {
            ++i;
        }
    }
    return parts;
}

std::string clef_id_for(const ChosenClef& chosen, double tempo) {
    if (tempo == chosen.clef.tempo) {
        return chosen.name;
    }
    // Room for the suffix within the id limit.
    const std::string suffix = "-" + bpm_label(tempo);
    return chosen.name.substr(0, limits::id_chars - suffix.size()) + suffix;
}

int nearest_number(const Clef& clef, double strength) {
    double peak = 0.0;
    for (const double amplitude : clef.numbers) {
        peak = std::max(peak, std::abs(amplitude));
    }
    const double target = strength * peak;
    int best = 1;
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        if (std::abs(clef.numbers[n] - target) <
            std::abs(clef.numbers[static_cast<std::size_t>(best - 1)] - target)) {
            best = static_cast<int>(n + 1);
        }
    }
    return best;
}

ImportedScore build_score(std::vector<GridNote> notes, std::vector<TempoChange> tempi,
                          std::int64_t total_ticks, const ChosenClef& chosen, std::string title,
                          const std::string& file) {
    for (auto& change : tempi) {
        change.tempo = std::clamp(change.tempo, limits::min_tempo_s, limits::max_tempo_s);
    }
    std::stable_sort(notes.begin(), notes.end(),
                     [](const GridNote& a, const GridNote& b) { return a.start < b.start; });
    check_length(notes, tempi, total_ticks, file);
    // One voice: a note that starts while another sounds cuts it short; of notes starting
    // together the last one stays.
    std::vector<GridNote> voice;
    for (const auto& note : notes) {
        if (!voice.empty() && voice.back().start == note.start) {
            voice.back() = note;
            continue;
        }
        if (!voice.empty() && voice.back().start + voice.back().length > note.start) {
            voice.back().length = note.start - voice.back().start;
        }
        voice.push_back(note);
    }
    // Each note of the one voice is a symbol at least (of a chord, one note is).
    if (voice.size() > limits::symbols) {
        too_long(file, std::to_string(voice.size()) + " notes; " + symbols_limit());
    }
    for (std::size_t i = 0; i < voice.size(); ++i) {
        voice[i].length = std::max<std::int64_t>(voice[i].length, 1);
        const bool abuts =
            i + 1 < voice.size() && voice[i].start + voice[i].length == voice[i + 1].start;
        if (!abuts) {
            voice[i].tie_to_next = GridNote::Tie::none;  // a tie needs a next note to reach
        }
    }

    std::vector<Written> sequence;
    std::int64_t now = 0;
    for (std::size_t i = 0; i < voice.size(); ++i) {
        const auto& note = voice[i];
        if (note.start > now) {
            sequence.push_back({Rest{}, note.start - now});
        }
        const GridNote* before = i > 0 && voice[i - 1].start + voice[i - 1].length == note.start
                                     ? &voice[i - 1]
                                     : nullptr;
        const GridNote* after =
            i + 1 < voice.size() && note.start + note.length == voice[i + 1].start ? &voice[i + 1]
                                                                                   : nullptr;
        const auto ramp = ramp_of(note, before, after, chosen.clef);
        const auto parts = lengths_for(note.length);
        std::int64_t done = 0;
        for (std::size_t p = 0; p < parts.size(); ++p) {
            Note written;
            written.length = parts[p];
            written.number = note.number;
            written.string = note.string;
            written.dynamics = note.dynamics;
            const bool last = p + 1 == parts.size();
            auto tie = last ? note.tie_to_next : GridNote::Tie::legato;
            // The parts of a note too long for one symbol are tied by legato; those of a hairpin
            // or a glide each take the level the ramp has reached, so the whole note still
            // ramps from its start to its end instead of reaching its level with the first part.
            if (ramp && parts.size() > 1) {
                const double from = static_cast<double>(done) / static_cast<double>(note.length);
                const double to = static_cast<double>(done + ticks_of(parts[p])) /
                                  static_cast<double>(note.length);
                const double at = note.dynamics == Dynamics::crescendo ? to : from;
                if (!(last && note.dynamics == Dynamics::crescendo) &&
                    !(p == 0 && note.dynamics != Dynamics::crescendo)) {
                    written.number = nearest_number(
                        chosen.clef, ramp->first + (ramp->second - ramp->first) * at);
                }
                if (!last && note.dynamics == Dynamics::none) {
                    tie = GridNote::Tie::portamento;
                }
            }
            done += ticks_of(parts[p]);
            sequence.push_back({written, ticks_of(parts[p]), tie});
        }
        now = note.start + note.length;
    }
    if (total_ticks > now) {
        sequence.push_back({Rest{}, total_ticks - now});
    }
    number_ties(sequence);
    BarLayout layout(tempi, chosen);
    for (const auto& written : sequence) {
        layout.add(written);
    }

    ImportedScore imported;
    imported.score.title = title.substr(0, limits::title_chars);
    const auto tempi_used = layout.tempi_used();
    imported.score.bars = std::move(layout).bars();
    for (const double tempo : tempi_used) {
        Clef clef = chosen.clef;
        clef.tempo = tempo;
        const auto id = clef_id_for(chosen, tempo);
        imported.score.clefs.push_back({id, ""});
        imported.clefs.push_back({id, clef, tempo != chosen.clef.tempo});
    }

    if (imported.score.bars.empty()) {
        throw DocumentError({file}, "holds no notes or rests to make a score of");
    }
    check_laid_out(imported, file);
    return imported;
}

}  // namespace vibscore::formats
