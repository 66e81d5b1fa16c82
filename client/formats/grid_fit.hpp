#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"

namespace vibscore::formats {

// Sound events in seconds (AHAP, Android) placed on the score's grid.
struct GridPlacement {
    double tempo = 1.0;  // seconds per quarter note that fit the events' times
    std::vector<GridNote> notes;
    std::int64_t total_ticks = 0;
    double worst_error = 0.0;  // seconds: how far the furthest time moved to reach the grid
};

// Chooses how a sound event's pitch lands on a string of the clef.
using StringOf = std::function<int(const SoundEvent&)>;

// Quantizes events into notes on the clef:
// - tempo: `tempo_hint` (a tempo the file records, as vibscore's AHAP exports do) or else the
//   clef's own, when every onset and every end that is not the default silence before the next
//   note lies on its 32nd-note grid (within a millisecond); otherwise the tempo that makes the
//   most common time between onsets a quarter note (or an 8th, half, 16th...) and fits; failing
//   that, the coarsest grid that holds every time to half a millisecond (Android's whole
//   milliseconds exactly); only times that fit none of these are rounded. It is always between
//   the limits a clef allows;
// - a gap before the next note no longer than the renderer's default silence is that silence,
//   not a rest; events that touch are tied (portamento where pitch or strength glides on into the
//   next note, legato otherwise);
// - a strength that rises is a crescendo, one that falls a decrescendo (unless it glides into
//   the next note); the number is the nearest to the note's own strength.
// `total` is the piece's length in seconds (rests at its end included), 0 for "the last note".
GridPlacement place_on_grid(std::vector<SoundEvent> events, double total, const Clef& clef,
                            const StringOf& string_of,
                            std::optional<double> tempo_hint = std::nullopt);

// Pitches (any scale: semitones, log frequency) to strings, keeping the melody's contour: up to
// `strings` distinct pitches each get their own string, spread over the staff from string 1;
// more are divided into `strings` equal bands between the lowest and highest.
std::vector<int> strings_by_contour(const std::vector<double>& pitches, int strings);

// The string of a sine clef whose frequency is nearest (in pitch, i.e. by ratio) to `frequency`.
int nearest_string(const Clef& clef, double frequency);

}  // namespace vibscore::formats
