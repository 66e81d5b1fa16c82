#include "client/editor/tap_rhythm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "client/formats/grid_fit.hpp"
#include "client/formats/score_builder.hpp"
#include "score/limits.hpp"

namespace vibscore::editor {

namespace {

double seconds(TapRecorder::Time time) {
    return std::chrono::duration<double>(time).count();
}

// Within this share of each other, two times between taps are the same length played twice
// (a dotted length is 33 % longer than the plain one below it).
constexpr double kSameLength = 0.12;
// A rhythm tapped this close to the clef's own tempo is at the clef's tempo.
constexpr double kClefTempoShare = 0.05;

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

// The quarter note the taps were played to: the most common time between two onsets (the
// importers' choice), the mean of the times within kSameLength of it.
double common_interval(const std::vector<double>& intervals) {
    double best = 0.0;
    std::size_t best_count = 0;
    for (const double x : intervals) {
        double sum = 0.0;
        std::size_t count = 0;
        for (const double y : intervals) {
            if (std::abs(y - x) <= kSameLength * x) {
                sum += y;
                ++count;
            }
        }
        // Of times as common as each other, the longest: quick taps are read as the shorter
        // notes between beats, not the beats.
        if (count > best_count || (count == best_count && sum / count > best)) {
            best = sum / static_cast<double>(count);
            best_count = count;
        }
    }
    return best;
}

// Onsets fitted to the 32nd-note grid of a tempo: the grid step and where it starts that put
// them nearest (least squares, refined from `tempo`), and the furthest any is from it, in units.
struct GridFit {
    double step = 0.0;  // a 32nd note, in seconds
    double origin = 0.0;
    double worst = 0.0;         // in `unit`s
    std::int64_t unit = 1;      // the finest length read between two taps, in 32nds
    std::vector<double> ticks;  // each onset's place on the grid, the first at 0
};

// The grid a release's end lands on, in 32nds: a 16th (or the finest length read, if longer).
constexpr std::int64_t kReleaseTicks = 2;

// How far refining may move a tempo from the one guessed.
constexpr double kMostTuned = 0.1;

// A thumb keeps time to some ±20 ms, so the time between two taps is ±40 ms: the finest length
// told apart between taps is the shortest of 32nd, 16th, 8th and quarter that is no shorter than
// this. Finer ones would write the same tapped interval two ways by where it falls.
constexpr double kFinestTapped = 0.09;

std::int64_t finest_unit(double step) {
    std::int64_t unit = 1;
    while (unit < formats::ticks_per_quarter && static_cast<double>(unit) * step < kFinestTapped) {
        unit *= 2;
    }
    return unit;
}

// Each tap's place counted from the one before it, by the time between them alone: the same
// interval is the same length wherever it falls, and an error does not add up.
std::vector<double> places(const std::vector<double>& onsets, double step, std::int64_t unit) {
    const double length = step * static_cast<double>(unit);
    std::vector<double> ks(onsets.size(), 0.0);
    for (std::size_t i = 1; i < onsets.size(); ++i) {
        const double units = std::max(1.0, std::round((onsets[i] - onsets[i - 1]) / length));
        ks[i] = ks[i - 1] + units * static_cast<double>(unit);
    }
    return ks;
}

GridFit fit_to_grid(const std::vector<double>& onsets, double tempo) {
    GridFit fit{tempo / formats::ticks_per_quarter, onsets.front(), 0.0, 1, {}};
    fit.unit = finest_unit(fit.step);
    const auto n = static_cast<double>(onsets.size());
    std::vector<double> ks(onsets.size(), 0.0);
    // Count each time between taps on the grid, fit the line through the taps, count again on
    // the line's grid: a guess a few per cent off settles in a few rounds.
    for (int round = 0; round < 3; ++round) {
        ks = places(onsets, fit.step, fit.unit);
        double sk = 0.0, st = 0.0, skk = 0.0, skt = 0.0;
        for (std::size_t i = 0; i < onsets.size(); ++i) {
            sk += ks[i];
            st += onsets[i];
            skk += ks[i] * ks[i];
            skt += ks[i] * onsets[i];
        }
        const double spread = n * skk - sk * sk;
        if (spread <= 0.0) {
            break;  // one place on the grid: nothing to refine the tempo by
        }
        const double fitted = (n * skt - sk * st) / spread;
        if (fitted <= 0.0) {
            break;
        }
        fit.step = fitted;
        fit.origin = (st - fitted * sk) / n;
    }
    ks = places(onsets, fit.step, fit.unit);
    for (std::size_t i = 0; i < onsets.size(); ++i) {
        fit.worst = std::max(fit.worst, std::abs(onsets[i] - fit.origin - ks[i] * fit.step) /
                                            (fit.step * static_cast<double>(fit.unit)));
    }
    fit.ticks = ks;
    // Refining only tunes the tempo guessed; one that wandered off found another grid.
    const double guessed = tempo / formats::ticks_per_quarter;
    if (std::abs(fit.step - guessed) > kMostTuned * guessed) {
        fit.worst = std::numeric_limits<double>::infinity();
    }
    return fit;
}

// How far from its grid a thumb's tap may land and still be read as on it, in the finest length
// read: under half of one, each lands on the nearest place, as it was meant.
constexpr double kTapSlack = 0.48;

}  // namespace

void TapRecorder::press_select(Time at) {
    taps_.push_back({true, at, std::nullopt});
}

void TapRecorder::release_select(Time at) {
    if (!taps_.empty() && taps_.back().note && !taps_.back().up && at >= taps_.back().down) {
        taps_.back().up = at;
    }
}

void TapRecorder::press_rest(Time at) {
    taps_.push_back({false, at, std::nullopt});
}

void TapRecorder::finish(Time at) {
    finished_ = at;
}

int TapRecorder::notes() const {
    return static_cast<int>(
        std::count_if(taps_.begin(), taps_.end(), [](const Tap& tap) { return tap.note; }));
}

std::vector<TapRecorder::Sound> TapRecorder::sounds() const {
    std::vector<Sound> found;
    if (taps_.empty()) {
        return found;
    }
    const double origin = seconds(taps_.front().down);
    std::vector<double> intervals;
    for (std::size_t i = 1; i < taps_.size(); ++i) {
        intervals.push_back(seconds(taps_[i].down) - seconds(taps_[i - 1].down));
    }
    const double usual = median(intervals);
    std::vector<double> silences;  // a thumb's time between letting go and pressing again
    for (std::size_t i = 0; i < taps_.size(); ++i) {
        const Tap& tap = taps_[i];
        const double down = seconds(tap.down) - origin;
        Sound sound{tap.note, down, down};
        if (i + 1 < taps_.size()) {
            const double next = seconds(taps_[i + 1].down) - origin;
            sound.end = next;
            if (tap.note && tap.up) {
                // In whole microseconds, as the clock gives them, so the edge is exact.
                const auto gap = taps_[i + 1].down - *tap.up;
                const auto shortest =
                    std::max<Time>(std::chrono::duration_cast<Time>(
                                       std::chrono::duration<double>(kShortestReleasedRest)),
                                   (taps_[i + 1].down - tap.down) / 4);
                if (gap >= shortest) {
                    sound.end = seconds(*tap.up) - origin;  // let go long enough: a rest
                } else {
                    silences.push_back(seconds(gap));
                }
            }
        } else if (tap.note && tap.up) {
            // The last note: its release, and the thumb's usual silence after it, as it left
            // that silence before every press.
            sound.end = seconds(*tap.up) - origin + median(silences);
        } else {
            const double finish = finished_ ? seconds(*finished_) - origin : down + usual;
            const double cap = usual > 0.0 ? down + usual : finish;
            sound.end = std::max(down, std::min(finish, cap));
        }
        found.push_back(sound);
    }
    return found;
}

TappedRhythm tapped_rhythm(const std::vector<TapRecorder::Sound>& sounds, double clef_tempo,
                           const std::string& clef_id, int string, int number) {
    TappedRhythm rhythm;
    if (sounds.empty()) {
        return rhythm;
    }
    std::vector<double> intervals;
    for (std::size_t i = 0; i < sounds.size(); ++i) {
        const double next = i + 1 < sounds.size() ? sounds[i + 1].onset : sounds[i].end;
        if (next > sounds[i].onset) {
            intervals.push_back(next - sounds[i].onset);
        }
    }
    std::vector<double> onsets;
    for (const auto& sound : sounds) {
        onsets.push_back(sound.onset);
    }
    // The importers' choice of tempo, with a thumb's slack: the most common time between taps as
    // a quarter note, else as an 8th, a half, ... whichever the taps fit first.
    const double common = common_interval(intervals);
    GridFit fit = fit_to_grid(onsets, common > 0.0 ? common : clef_tempo);
    if (common > 0.0) {
        for (const double as_beats : {1.0, 0.5, 2.0, 0.25, 1.5, 0.75, 4.0, 3.0}) {
            const GridFit candidate = fit_to_grid(onsets, common / as_beats);
            if (candidate.worst <= kTapSlack) {
                fit = candidate;
                break;
            }
        }
    }
    double tempo = fit.step * formats::ticks_per_quarter;
    if (clef_tempo > 0.0 && std::abs(tempo - clef_tempo) <= kClefTempoShare * clef_tempo) {
        tempo = clef_tempo;
        fit.step = tempo / formats::ticks_per_quarter;
    } else {
        // To a whole number of beats a minute, as a person counts a tempo (150, not 149.63, for
        // taps 401 ms apart): a beat a minute is 2.7 ms at 150, far below what a thumb keeps,
        // and the tempo clef made for it is named as it plays.
        tempo = 60.0 / std::max(1.0, std::round(60.0 / tempo));
    }
    tempo = std::clamp(tempo, limits::min_tempo_s, limits::max_tempo_s);

    // On the grid of that tempo, the times are exact: the importers' quantisation then keeps
    // the tempo and lays the notes and rests out in bars.
    const double grid = tempo / formats::ticks_per_quarter;
    std::vector<double> end_ticks(sounds.size());
    for (std::size_t i = 0; i < sounds.size(); ++i) {
        const double next = i + 1 < sounds.size() ? fit.ticks[i + 1] : HUGE_VAL;
        const bool to_next = i + 1 < sounds.size() && sounds[i].end >= sounds[i + 1].onset;
        // A thumb lets go less exactly than it presses: where a release ends a note, the end
        // goes to the nearest 16th (or the finest length read), counted from its own tap.
        const auto release = static_cast<double>(std::max(kReleaseTicks, fit.unit));
        const double held = (sounds[i].end - sounds[i].onset) / fit.step;
        end_ticks[i] = to_next ? next
                               : std::clamp(fit.ticks[i] + release * std::round(held / release),
                                            std::min(fit.ticks[i] + 1.0, next), next);
    }
    std::vector<formats::SoundEvent> events;
    for (std::size_t i = 0; i < sounds.size(); ++i) {
        if (!sounds[i].note) {
            continue;
        }
        formats::SoundEvent event;
        event.onset = fit.ticks[i] * grid;
        const double end = end_ticks[i] * grid;
        const bool runs_on =
            i + 1 < sounds.size() && sounds[i + 1].note && end_ticks[i] >= fit.ticks[i + 1];
        // Up to the next tap, with the default silence between: not tied to it.
        event.duration = std::max(0.0, runs_on ? end - event.onset - 0.001 : end - event.onset);
        event.strength = event.strength_start = event.strength_end = 1.0;
        events.push_back(event);
    }
    const double total = end_ticks.back() * grid;
    Clef clef;
    clef.tempo = tempo;
    clef.numbers = {1.0};
    const auto placement = formats::place_on_grid(
        events, total, clef, [&](const formats::SoundEvent&) { return string; });
    auto notes = placement.notes;
    for (auto& note : notes) {
        note.number = number;
        note.string = string;
    }
    const auto built =
        formats::build_score(std::move(notes), {{0, placement.tempo}}, placement.total_ticks,
                             {clef_id, clef}, "tapped", "the tapped rhythm");
    rhythm.tempo = placement.tempo;
    rhythm.bars = built.score.bars;
    for (auto& bar : rhythm.bars) {
        bar.clef = clef_id;
        for (const auto& symbol : bar.symbols) {
            rhythm.notes += std::holds_alternative<Note>(symbol) ? 1 : 0;
            rhythm.rests += std::holds_alternative<Rest>(symbol) ? 1 : 0;
        }
    }
    return rhythm;
}

}  // namespace vibscore::editor
