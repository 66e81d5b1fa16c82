#include "score/pattern_score.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "score/document_error.hpp"
#include "score/limits.hpp"
#include "score/score_xml.hpp"

namespace vibscore {

namespace {

// A 32nd note at the shortest tempo a clef may have: the finest time a score can hold.
constexpr double kShortest_s = limits::min_tempo_s / 8.0;
// Longer stretches are split into notes of at most this (a clef's longest tempo).
constexpr double kLongestNote_s = limits::max_tempo_s;
constexpr double kSameLevel = 1e-9;

bool same(double a, double b) {
    return std::abs(a - b) < kSameLevel;
}

bool sounds(const PatternStep& step) {
    return step.from > 0.0 || step.to > 0.0;
}

// The pattern with its levels in 0..1, frequencies a sine clef can hold (else the actuator's
// own) and stretches too short for a score left out.
VibrationPattern cleaned(const VibrationPattern& pattern) {
    VibrationPattern steps;
    for (auto step : pattern) {
        if (!(step.seconds >= kShortest_s)) {
            continue;
        }
        step.from = std::isfinite(step.from) ? std::clamp(step.from, 0.0, 1.0) : 0.0;
        step.to = std::isfinite(step.to) ? std::clamp(step.to, 0.0, 1.0) : 0.0;
        if (!(step.frequency_hz > 0.0 && step.frequency_hz <= limits::max_frequency_hz)) {
            step.frequency_hz = 0.0;
        }
        steps.push_back(step);
    }
    return steps;
}

// ---- exact_pattern_score ----

enum class Tie { none, legato, portamento };

struct PlannedNote {
    double seconds = 0.0;
    double level = 0.0;
    double frequency_hz = 0.0;
    bool rest = false;
    Tie tie = Tie::none;  // to the next planned note
};

// Each step as notes (or rests) of at most kLongestNote_s, with how each is tied to the next.
// A ramp glides (portamento) into the note after it, which must start at the ramp's final
// strength: the next step's first note when the pattern continues from there, else a note of
// kShortest_s taken from the ramp's end.
std::vector<PlannedNote> plan_notes(const VibrationPattern& steps) {
    std::vector<PlannedNote> notes;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const PatternStep& step = steps[i];
        const PatternStep* next = i + 1 < steps.size() ? &steps[i + 1] : nullptr;
        const bool next_sounds = next != nullptr && sounds(*next);
        double seconds = step.seconds;
        const int pieces_for_rest = static_cast<int>(std::ceil(seconds / kLongestNote_s));
        if (!sounds(step)) {
            for (int p = 0; p < pieces_for_rest; ++p) {
                notes.push_back({seconds / pieces_for_rest, 0.0, 0.0, true, Tie::none});
            }
            continue;
        }
        bool ramp = !same(step.from, step.to);
        const bool next_continues =
            next_sounds && same(next->from, step.to) && same(next->frequency_hz, step.frequency_hz);
        bool own_target = ramp && !next_continues;
        if (own_target) {
            if (seconds >= 2 * kShortest_s) {
                seconds -= kShortest_s;
            } else {
                ramp = own_target = false;  // too short to ramp: held at its start
            }
        }
        const int pieces = static_cast<int>(std::ceil(seconds / kLongestNote_s));
        const Tie tie_after_step = ramp ? Tie::portamento : next_sounds ? Tie::legato : Tie::none;
        for (int p = 0; p < pieces; ++p) {
            PlannedNote note;
            note.seconds = seconds / pieces;
            note.level = step.from + (step.to - step.from) * p / pieces;
            note.frequency_hz = step.frequency_hz;
            note.tie = p + 1 < pieces ? (ramp ? Tie::portamento : Tie::legato) : tie_after_step;
            notes.push_back(note);
        }
        if (own_target) {
            notes.push_back({kShortest_s, step.to, step.frequency_hz, false,
                             next_sounds ? Tie::legato : Tie::none});
        }
    }
    return notes;
}

Clef clef_for(const PlannedNote& note, double tempo) {
    Clef clef;
    clef.tempo = tempo;
    clef.numbers = {note.level};
    if (note.frequency_hz > 0.0) {
        clef.type = ClefType::sine;
        clef.strings = {ClefString{note.frequency_hz, {}}};
    } else {
        // A level line at full height: the drive is the number itself, at the actuator's own
        // frequency (docs/score-format.md, the envelope view).
        clef.type = ClefType::line;
        clef.strings = {ClefString{0.0, {{0.0, 1.0}, {1.0, 1.0}}}};
    }
    return clef;
}

// ---- pattern_on_clef ----

// The ten lengths in 32nd notes, longest first: any whole number of 32nds is a sum of them.
constexpr std::array<std::pair<Length, long>, length_count> kLengthsIn32nds{{
    {Length::whole, 32},
    {Length::half_dot, 24},
    {Length::half, 16},
    {Length::quarter_dot, 12},
    {Length::quarter, 8},
    {Length::eighth_dot, 6},
    {Length::eighth, 4},
    {Length::sixteenth_dot, 3},
    {Length::sixteenth, 2},
    {Length::thirty_second, 1},
}};

std::vector<Length> lengths_for(long thirty_seconds) {
    std::vector<Length> lengths;
    for (const auto& [length, units] : kLengthsIn32nds) {
        while (thirty_seconds >= units) {
            lengths.push_back(length);
            thirty_seconds -= units;
        }
    }
    return lengths;
}

// Runs of equal clef numbers (0: rest) on the 32nd-note grid.
struct Run {
    long ticks = 0;
    int number = 0;
};

void append_run(std::vector<Run>& runs, long ticks, int number) {
    if (ticks <= 0) {
        return;
    }
    if (!runs.empty() && runs.back().number == number) {
        runs.back().ticks += ticks;
    } else {
        runs.push_back({ticks, number});
    }
}

}  // namespace

double pattern_seconds(const VibrationPattern& pattern) {
    double seconds = 0.0;
    for (const auto& step : pattern) {
        seconds += std::max(step.seconds, 0.0);
    }
    return seconds;
}

ScoreBundle exact_pattern_score(const VibrationPattern& pattern, const std::string& title,
                                const std::string& file) {
    const auto notes = plan_notes(cleaned(pattern));
    Score score;
    score.title = title;
    std::map<std::string, Clef, std::less<>> clefs;
    std::map<std::tuple<double, double, double, bool>, std::string> clef_ids;
    std::int64_t legato = 0, portamento = 0;
    Tie tie_in = Tie::none;  // how the previous note is tied to this one
    for (const auto& planned : notes) {
        // A note shorter than the shortest tempo is a 32nd of a faster clef.
        const bool short_note = planned.seconds < limits::min_tempo_s;
        const double tempo = short_note ? planned.seconds * 8.0 : planned.seconds;
        const auto key = std::make_tuple(tempo, planned.level, planned.frequency_hz, planned.rest);
        auto [found, added] = clef_ids.try_emplace(key, "c" + std::to_string(clef_ids.size() + 1));
        if (added) {
            clefs.emplace(found->second, clef_for(planned, tempo));
            score.clefs.push_back({found->second, found->second + ".clef.xml"});
        }
        Bar bar;
        bar.clef = found->second;
        const Length length = short_note ? Length::thirty_second : Length::quarter;
        if (planned.rest) {
            bar.symbols.emplace_back(Rest{length});
        } else {
            Note note;
            note.length = length;
            // A serial continues a run of ties of its kind, or starts a new one.
            if (tie_in == Tie::legato) {
                note.legato = legato;
            } else if (planned.tie == Tie::legato) {
                note.legato = ++legato;
            }
            if (tie_in == Tie::portamento) {
                note.portamento = portamento;
            } else if (planned.tie == Tie::portamento) {
                note.portamento = ++portamento;
            }
            bar.symbols.emplace_back(note);
        }
        tie_in = planned.rest ? Tie::none : planned.tie;
        score.bars.push_back(std::move(bar));
    }
    // Through the document reader, so a generated score meets every rule a written one does.
    return bind_clefs(read_score(write_score(score), file), file,
                      [&](const ClefDeclaration& declaration, const SourceLocation&) {
                          return clefs.at(declaration.id);
                      });
}

ScoreOnClef pattern_on_clef(const VibrationPattern& pattern, const std::string& title,
                            const std::string& clef_href, const Clef& clef) {
    const auto steps = cleaned(pattern);
    double peak = 0.0;
    for (const auto& step : steps) {
        peak = std::max({peak, step.from, step.to});
    }
    const double top =
        clef.numbers.empty() ? 1.0 : *std::max_element(clef.numbers.begin(), clef.numbers.end());
    const auto number_for = [&](double level) {
        if (peak <= 0.0 || level <= 0.0) {
            return 0;
        }
        const double wanted = level / peak * top;
        int best = 0;
        double best_distance = wanted;  // the distance to a rest
        for (std::size_t i = 0; i < clef.numbers.size(); ++i) {
            const double distance = std::abs(clef.numbers[i] - wanted);
            if (distance < best_distance) {
                best = static_cast<int>(i) + 1;
                best_distance = distance;
            }
        }
        return best;
    };

    const double tick = clef.tempo / 8.0;
    std::vector<Run> runs;
    double start = 0.0;
    long start_tick = 0;
    for (const auto& step : steps) {
        const double end = start + step.seconds;
        // Step ends are rounded from their exact times, so rounding never accumulates.
        const long end_tick = std::lround(end / tick);
        const long ticks = end_tick - start_tick;
        if (same(step.from, step.to)) {
            append_run(runs, ticks, number_for(step.from));
        } else {
            for (long t = 0; t < ticks; ++t) {
                const double at = (static_cast<double>(t) + 0.5) / static_cast<double>(ticks);
                append_run(runs, 1, number_for(step.from + (step.to - step.from) * at));
            }
        }
        start = end;
        start_tick = end_tick;
    }

    Score score;
    score.title = title;
    score.clefs.push_back({"v", clef_href});
    Bar bar;
    bar.clef = "v";
    std::int64_t legato = 0;
    bool tied_in = false;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const auto lengths = lengths_for(runs[r].ticks);
        if (runs[r].number == 0) {
            for (const Length length : lengths) {
                bar.symbols.emplace_back(Rest{length});
            }
            tied_in = false;
            continue;
        }
        const bool next_sounds = r + 1 < runs.size() && runs[r + 1].number != 0;
        for (std::size_t l = 0; l < lengths.size(); ++l) {
            Note note;
            note.length = lengths[l];
            note.number = runs[r].number;
            note.string = 1;
            const bool tied_out = l + 1 < lengths.size() || next_sounds;
            if (tied_in || tied_out) {
                note.legato = tied_in ? legato : ++legato;
            }
            bar.symbols.emplace_back(note);
            tied_in = tied_out;
        }
    }
    score.bars.push_back(std::move(bar));
    return {write_score(score), peak > 0.0 ? peak : 1.0};
}

}  // namespace vibscore
