#include "client/formats/grid_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "client/formats/envelope_notes.hpp"
#include "daemon/render/performance.hpp"
#include "score/limits.hpp"

namespace vibscore::formats {

namespace {

// Android counts whole milliseconds, so a time may be half of one off; a millisecond of slack
// covers that and float noise.
constexpr double kTimeSlack = 0.001;
// Strength and pitch changes smaller than this are noise from 8-bit or float storage.
constexpr double kChangeSlack = 0.004;

double grid_error(const std::vector<double>& times, double grid) {
    double worst = 0.0;
    for (const double t : times) {
        worst = std::max(worst, std::abs(t - std::round(t / grid) * grid));
    }
    return worst;
}

bool fits(const std::vector<double>& times, double tempo) {
    const double grid = tempo / ticks_per_quarter;
    return grid_error(times, grid) <= std::max(kTimeSlack, 0.02 * grid);
}

// Fits without moving any time by more than half a millisecond: whole milliseconds stay apart.
bool fits_closely(const std::vector<double>& times, double tempo) {
    return grid_error(times, tempo / ticks_per_quarter) <= kTimeSlack / 2 + 1e-9;
}

double clamp_tempo(double tempo) {
    return std::clamp(tempo, limits::min_tempo_s, limits::max_tempo_s);
}

// Whether every time lies on a grid of `grid` seconds within `slack`.
bool on_grid(const std::vector<double>& times, double grid, double slack) {
    for (const double t : times) {
        if (std::abs(t - std::round(t / grid) * grid) > slack) {
            return false;
        }
    }
    return true;
}

// The most common time between onsets (or, with fewer than two onsets, between the times), in
// seconds; 0 when there is none.
double common_interval(const std::vector<double>& onsets, const std::vector<double>& times) {
    std::vector<double> points = onsets.size() >= 2 ? onsets : times;
    std::sort(points.begin(), points.end());
    std::map<long long, int> counts;  // intervals in microseconds
    for (std::size_t i = 1; i < points.size(); ++i) {
        const auto interval = std::llround((points[i] - points[i - 1]) * 1e6);
        if (interval > 0) {
            ++counts[interval];
        }
    }
    if (counts.empty()) {
        return 0.0;
    }
    return static_cast<double>(std::max_element(counts.begin(), counts.end(),
                                                [](auto a, auto b) { return a.second < b.second; })
                                   ->first) /
           1e6;
}

// The coarsest grid that holds every time: for times in whole milliseconds (Android's), their
// greatest common divisor, exactly; for others, the shortest time between two times divided
// into up to kMaxDivisions parts, to half a millisecond (so that times a millisecond apart stay
// apart). Nothing when neither holds them, or when the piece would need more ticks on the grid
// than a score's bars hold.
std::optional<double> coarsest_grid(const std::vector<double>& times) {
    constexpr int kMaxDivisions = 64;
    constexpr double kHalfMs = kTimeSlack / 2;
    std::vector<double> sorted = times;
    std::sort(sorted.begin(), sorted.end());
    const double last = sorted.empty() ? 0.0 : sorted.back();
    const auto holds = [&](double grid, double slack) {
        return grid >= limits::min_tempo_s / ticks_per_quarter &&
               last / grid <= static_cast<double>(max_import_ticks) && on_grid(times, grid, slack);
    };
    long long divisor = 0;
    bool whole_ms = true;
    for (const double t : times) {
        const double ms = t * 1000.0;
        whole_ms = whole_ms && std::abs(ms - std::round(ms)) <= 1e-6;
        divisor = std::gcd(divisor, std::llround(ms));
    }
    if (whole_ms && divisor > 0) {
        const double grid = static_cast<double>(divisor) / 1000.0;
        return holds(grid, 1e-6) ? std::optional<double>(grid) : std::nullopt;
    }
    double shortest = 0.0;
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        const double step = sorted[i] - sorted[i - 1];
        if (step > kHalfMs && (shortest == 0.0 || step < shortest)) {
            shortest = step;
        }
    }
    for (int parts = 1; shortest > 0.0 && parts <= kMaxDivisions; ++parts) {
        if (holds(shortest / parts, kHalfMs)) {
            return shortest / parts;
        }
    }
    return std::nullopt;
}

// The tempo whose grid the times sit on: the hint's (a tempo the file records), the clef's, one
// that makes the most common time between onsets a quarter note (or an 8th, half, ...), or one
// whose grid is the coarsest that holds every time; only irregular times with none of those
// are rounded to the common interval's grid.
double fit_tempo(const std::vector<double>& times, const std::vector<double>& onsets,
                 double clef_tempo, std::optional<double> hint) {
    if (hint && *hint >= limits::min_tempo_s && *hint <= limits::max_tempo_s &&
        fits(times, *hint)) {
        return *hint;
    }
    if (fits(times, clef_tempo)) {
        return clef_tempo;
    }
    const double common = common_interval(onsets, times);
    if (common <= 0.0) {
        return clef_tempo;
    }
    // The common interval as a quarter first, then as the lengths nearest to it: one that
    // moves no time by more than half a millisecond.
    constexpr double kAsBeats[] = {1.0, 0.5, 2.0, 0.25, 1.5, 0.75, 4.0, 3.0, 0.125, 0.375};
    for (const double as_beats : kAsBeats) {
        const double tempo = clamp_tempo(common / as_beats);
        if (fits_closely(times, tempo)) {
            return tempo;
        }
    }
    // A grid that holds every time, with the common interval as near a quarter note as a whole
    // number of its steps allows: Android's 10-12 ms steps stay 10-12 ms.
    if (const auto grid = coarsest_grid(times)) {
        const double steps = std::max(1.0, std::round(common / *grid));
        const double per_step = std::max(1.0, std::round(ticks_per_quarter / steps));
        return clamp_tempo(*grid * ticks_per_quarter / per_step);
    }
    // Then one that moves times by up to the millisecond of slack.
    for (const double as_beats : kAsBeats) {
        const double tempo = clamp_tempo(common / as_beats);
        if (fits(times, tempo)) {
            return tempo;
        }
    }
    // Irregular times: keep the common interval a quarter note and round to its grid.
    return clamp_tempo(common);
}

bool changes(double from, double to) {
    return std::abs(to - from) > kChangeSlack;
}

}  // namespace

GridPlacement place_on_grid(std::vector<SoundEvent> events, double total, const Clef& clef,
                            const StringOf& string_of, std::optional<double> tempo_hint) {
    std::stable_sort(events.begin(), events.end(),
                     [](const auto& a, const auto& b) { return a.onset < b.onset; });
    const render::RenderOptions defaults;
    const std::size_t n = events.size();
    // How each note ends: at the next onset (touching: tied; within the default silence: not
    // tied, no rest) or at its own end, a rest following.
    std::vector<bool> tied(n, false), runs_on(n, false);
    std::vector<double> times, onsets;
    for (std::size_t i = 0; i < n; ++i) {
        auto& event = events[i];
        onsets.push_back(event.onset);
        times.push_back(event.onset);
        if (i + 1 < n) {
            const double next = events[i + 1].onset;
            event.duration = std::min(event.duration, next - event.onset);  // one voice
            const double gap = next - event.end();
            const double silence = std::min(
                defaults.separation_s, defaults.separation_max_fraction * (next - event.onset));
            tied[i] = gap <= 1e-9 && event.duration > 0.0;
            runs_on[i] = tied[i] || (event.duration > 0.0 && gap <= silence + kTimeSlack);
        }
        if (!runs_on[i] && event.duration > 0.0) {
            times.push_back(event.end());
        }
    }
    const double last_end = n > 0 ? events.back().end() : 0.0;
    if (total > last_end) {
        times.push_back(total);
    }

    GridPlacement placement;
    placement.tempo = fit_tempo(times, onsets, clef.tempo, tempo_hint);
    const double grid = placement.tempo / ticks_per_quarter;
    placement.worst_error = grid_error(times, grid);
    const auto tick = [&](double t) { return static_cast<std::int64_t>(std::llround(t / grid)); };

    Dynamics previous = Dynamics::none;
    for (std::size_t i = 0; i < n; ++i) {
        const auto& event = events[i];
        GridNote note;
        note.start = tick(event.onset);
        const std::int64_t end = runs_on[i] ? tick(events[i + 1].onset) : tick(event.end());
        note.length = std::max<std::int64_t>(1, end - note.start);
        note.string = string_of(event);

        const double from = event.strength_start, to = event.strength_end;
        const bool glides_pitch = tied[i] && changes(event.pitch_start, event.pitch_end);
        const bool glides_strength = tied[i] && changes(from, to) && to > kChangeSlack &&
                                     !changes(to, events[i + 1].strength_start);
        if (!event.strength_points.empty()) {
            const auto tie_out = !tied[i]                          ? GridNote::Tie::none
                                 : glides_pitch || glides_strength ? GridNote::Tie::portamento
                                                                   : GridNote::Tie::legato;
            std::vector<EnvelopePoint> points{{note.start, from}};
            for (const auto& [at, level] : event.strength_points) {
                points.push_back(
                    {std::clamp(tick(at), note.start, note.start + note.length), level});
            }
            points.push_back({note.start + note.length, to});
            const bool after_crescendo =
                !placement.notes.empty() &&
                placement.notes.back().dynamics == Dynamics::crescendo &&
                placement.notes.back().start + placement.notes.back().length == note.start;
            auto shaped =
                notes_for_envelope(std::move(points), note.string, clef, after_crescendo, tie_out);
            placement.shaped.push_back(
                {event.onset, shaped.pieces, shaped.worst_level_error, shaped.early_ramps});
            previous = shaped.notes.empty() ? Dynamics::none : shaped.notes.back().dynamics;
            placement.notes.insert(placement.notes.end(), shaped.notes.begin(), shaped.notes.end());
            continue;
        }
        // A hairpin goes on only through notes tied into this one: after a gap, a rise that
        // glides in pitch is the glide's own, whatever the note before did.
        const Dynamics before = i > 0 && tied[i - 1] ? previous : Dynamics::none;
        // On one pitch, a straight ramp between two sounding levels is no hairpin: a crescendo
        // would rise from silence, a decrescendo fall to it. Into the next note at the level it
        // reaches, it is a glide (portamento); a fall that the next note goes on with (however
        // little) is a decrescendo on into it; otherwise it is a glide that reaches its level a
        // 32nd early.
        const bool next_falls = tied[i] && !changes(to, events[i + 1].strength_start) &&
                                events[i + 1].strength_end < to - 1e-9;
        const bool rise_between =
            to > from && changes(from, to) && changes(from, 0.0) && before != Dynamics::crescendo;
        const bool fall_between = to < from && changes(from, to) && changes(to, 0.0) && !next_falls;
        if (!glides_pitch && !glides_strength && (rise_between || fall_between) &&
            note.length >= 2) {
            const auto tie_out = tied[i] ? GridNote::Tie::legato : GridNote::Tie::none;
            auto shaped = notes_for_envelope({{note.start, from}, {note.start + note.length, to}},
                                             note.string, clef, false, tie_out);
            placement.shaped.push_back(
                {event.onset, shaped.pieces, shaped.worst_level_error, shaped.early_ramps});
            previous = shaped.notes.empty() ? Dynamics::none : shaped.notes.back().dynamics;
            placement.notes.insert(placement.notes.end(), shaped.notes.begin(), shaped.notes.end());
            continue;
        }
        double own = from;
        if (!changes(from, to)) {
            note.dynamics = Dynamics::none;
        } else if (to > from) {
            // A rise that starts from silence, or goes on from a crescendo, is a crescendo;
            // one from a sounding strength that glides in pitch into the next note is part of
            // that glide. On one pitch a ramp is a hairpin: it sounds the same, and reads as
            // the score most likely wrote it.
            const bool crescendo = (!glides_pitch && !rise_between) || !changes(from, 0.0) ||
                                   before == Dynamics::crescendo;
            note.dynamics = crescendo ? Dynamics::crescendo : Dynamics::none;
            own = crescendo ? to : from;
        } else {
            note.dynamics = (glides_pitch && changes(to, 0.0) && before != Dynamics::decrescendo) ||
                                    (!glides_pitch && fall_between)
                                ? Dynamics::none
                                : Dynamics::decrescendo;
        }
        previous = note.dynamics;
        note.number = nearest_number(clef, own);
        // Tied notes glide (portamento) when the pitch moves on, or when the strength does and
        // no hairpin explains it; otherwise they are joined by legato.
        if (!tied[i]) {
            note.tie_to_next = GridNote::Tie::none;
        } else if (glides_pitch || (glides_strength && note.dynamics == Dynamics::none)) {
            note.tie_to_next = GridNote::Tie::portamento;
        } else {
            note.tie_to_next = GridNote::Tie::legato;
        }
        placement.notes.push_back(note);
    }
    placement.total_ticks = tick(std::max(total, last_end));
    return placement;
}

std::string shape_note(const ShapedEvent& shaped, const std::string& curve) {
    std::string note = "the event at " + seconds_text(shaped.onset) + ": its " + curve + ", in " +
                       std::to_string(shaped.pieces) +
                       (shaped.pieces == 1 ? " straight piece" : " straight pieces") +
                       ", is tied notes with glides and hairpins";
    if (shaped.worst_level_error >= 0.005) {
        char off[32];
        std::snprintf(off, sizeof off, "%.2f", shaped.worst_level_error);
        note += "; levels to the nearest numbers (at most " + std::string(off) + " of full off)";
    }
    if (shaped.early_ramps > 0) {
        note += "; " + std::to_string(shaped.early_ramps) +
                (shaped.early_ramps == 1 ? " ramp that no hairpin draws reaches its level"
                                         : " ramps that no hairpin draws reach their level") +
                " a 32nd early";
    }
    return note;
}

std::vector<int> strings_by_contour(const std::vector<double>& pitches, int strings) {
    const std::set<double> distinct(pitches.begin(), pitches.end());
    std::vector<int> result;
    if (distinct.empty()) {
        return result;
    }
    const double low = *distinct.begin();
    const double high = *distinct.rbegin();
    const auto count = static_cast<int>(distinct.size());
    for (const double pitch : pitches) {
        int string = 1;
        if (count <= strings) {
            const auto rank =
                static_cast<int>(std::distance(distinct.begin(), distinct.find(pitch)));
            string = count == 1 ? 1
                                : 1 + static_cast<int>(std::lround(static_cast<double>(rank) *
                                                                   (strings - 1) / (count - 1)));
        } else {
            string = 1 + static_cast<int>(std::floor((pitch - low) / (high - low) * strings));
        }
        result.push_back(std::clamp(string, 1, strings));
    }
    return result;
}

int nearest_string(const Clef& clef, double frequency) {
    int best = 1;
    double best_distance = INFINITY;
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        const double distance = std::abs(std::log(frequency / clef.strings[s].frequency));
        if (distance < best_distance) {
            best_distance = distance;
            best = static_cast<int>(s + 1);
        }
    }
    return best;
}

}  // namespace vibscore::formats
