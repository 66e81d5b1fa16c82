#include "client/formats/envelope_notes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vibscore::formats {

namespace {

// Levels closer than this are one level: the numbers of a clef lie further apart.
constexpr double kLevelSlack = 0.01;

bool silent(double level) {
    return level <= kLevelSlack;
}

struct Segment {
    std::int64_t start = 0, end = 0;
    double from = 0.0, to = 0.0;

    bool rises() const { return to > from + kLevelSlack; }
    bool falls() const { return to < from - kLevelSlack; }
    bool flat() const { return !rises() && !falls(); }
};

// Of several points at one tick the first and the last stay: the level reached, then the level
// jumped to. A point on the straight line between its neighbours says nothing more.
std::vector<EnvelopePoint> simplified(const std::vector<EnvelopePoint>& points) {
    std::vector<EnvelopePoint> kept;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const bool first_at_tick = i == 0 || points[i - 1].tick != points[i].tick;
        const bool last_at_tick = i + 1 == points.size() || points[i + 1].tick != points[i].tick;
        if (first_at_tick || last_at_tick) {
            kept.push_back(points[i]);
        }
    }
    std::vector<EnvelopePoint> lean;
    for (std::size_t i = 0; i < kept.size(); ++i) {
        if (i > 0 && i + 1 < kept.size() && !lean.empty() && lean.back().tick < kept[i].tick &&
            kept[i].tick < kept[i + 1].tick) {
            const auto& a = lean.back();
            const auto& b = kept[i + 1];
            const double along =
                static_cast<double>(kept[i].tick - a.tick) / static_cast<double>(b.tick - a.tick);
            if (std::abs(a.level + (b.level - a.level) * along - kept[i].level) <= kLevelSlack) {
                continue;
            }
        }
        lean.push_back(kept[i]);
    }
    return lean;
}

}  // namespace

double number_level(const Clef& clef, int number) {
    double peak = 0.0;
    for (const double amplitude : clef.numbers) {
        peak = std::max(peak, std::abs(amplitude));
    }
    return peak > 0.0 ? clef.numbers.at(static_cast<std::size_t>(number - 1)) / peak : 0.0;
}

ShapedNotes notes_for_envelope(std::vector<EnvelopePoint> points, int string, const Clef& clef,
                               bool after_crescendo, GridNote::Tie tie_out) {
    ShapedNotes shaped;
    points = simplified(points);
    std::vector<Segment> segments;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        if (points[i + 1].tick > points[i].tick) {
            segments.push_back(
                {points[i].tick, points[i + 1].tick, points[i].level, points[i + 1].level});
        }
    }
    shaped.pieces = static_cast<int>(segments.size());
    if (segments.empty()) {
        // A curve within one tick: one note at its strongest.
        double level = 0.0;
        for (const auto& point : points) {
            level = std::max(level, point.level);
        }
        const std::int64_t start = points.empty() ? 0 : points.front().tick;
        shaped.notes.push_back(
            {start, 1, string, nearest_number(clef, level), Dynamics::none, tie_out});
        return shaped;
    }
    const auto continuous = [&](std::size_t i) {
        return i + 1 < segments.size() && segments[i].end == segments[i + 1].start &&
               std::abs(segments[i + 1].from - segments[i].to) <= kLevelSlack;
    };
    // A fall is a decrescendo when it ends in silence or flows into one: decided from the end.
    std::vector<bool> decrescendo(segments.size(), false);
    for (std::size_t i = segments.size(); i-- > 0;) {
        decrescendo[i] = segments[i].falls() &&
                         (silent(segments[i].to) || (continuous(i) && decrescendo[i + 1]));
    }
    const auto number_for = [&](double level) {
        const int number = nearest_number(clef, level);
        shaped.worst_level_error =
            std::max(shaped.worst_level_error, std::abs(number_level(clef, number) - level));
        return number;
    };
    const auto add = [&](std::int64_t start, std::int64_t end, int number, Dynamics dynamics,
                         GridNote::Tie tie) {
        if (!shaped.notes.empty()) {
            auto& before = shaped.notes.back();
            if (before.start + before.length != start) {
                before.tie_to_next = GridNote::Tie::none;
            } else if (before.tie_to_next == GridNote::Tie::none) {
                before.tie_to_next = GridNote::Tie::legato;
            }
        }
        shaped.notes.push_back({start, end - start, string, number, dynamics, tie});
    };
    bool crescendo_before = after_crescendo;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const auto& segment = segments[i];
        const bool touches_before =
            i == 0 || (!shaped.notes.empty() &&
                       shaped.notes.back().start + shaped.notes.back().length == segment.start);
        // The renderer goes on from a crescendo note that this one follows directly.
        const bool follows_crescendo = crescendo_before && touches_before;
        const bool goes_on_crescendo = follows_crescendo && (i == 0 || continuous(i - 1));
        crescendo_before = false;
        if (segment.flat()) {
            if (!silent(segment.from)) {  // silence is a rest, not the weakest number
                add(segment.start, segment.end, number_for(segment.from), Dynamics::none,
                    GridNote::Tie::none);
            }
        } else if (segment.rises() &&
                   (goes_on_crescendo || (silent(segment.from) && !follows_crescendo))) {
            add(segment.start, segment.end, number_for(segment.to), Dynamics::crescendo,
                GridNote::Tie::none);
            crescendo_before = true;
        } else if (decrescendo[i]) {
            add(segment.start, segment.end, number_for(segment.from), Dynamics::decrescendo,
                GridNote::Tie::none);
        } else if (continuous(i)) {
            // The glide ends on the next note's number: the level the next segment starts at.
            add(segment.start, segment.end, number_for(segment.from), Dynamics::none,
                GridNote::Tie::portamento);
        } else if (segment.end - segment.start >= 2) {
            add(segment.start, segment.end - 1, number_for(segment.from), Dynamics::none,
                GridNote::Tie::portamento);
            add(segment.end - 1, segment.end, number_for(segment.to), Dynamics::none,
                GridNote::Tie::none);
            ++shaped.early_ramps;
        } else {
            add(segment.start, segment.end, number_for(segment.to), Dynamics::none,
                GridNote::Tie::none);
            ++shaped.early_ramps;
        }
    }
    if (!shaped.notes.empty()) {
        auto& last = shaped.notes.back();
        last.tie_to_next =
            last.start + last.length == points.back().tick ? tie_out : GridNote::Tie::none;
    }
    return shaped;
}

}  // namespace vibscore::formats
