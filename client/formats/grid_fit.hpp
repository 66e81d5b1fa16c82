#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "client/formats/score_builder.hpp"
#include "client/formats/sound_events.hpp"

namespace vibscore::formats {

// An event whose strength bends (SoundEvent::strength_points), as the notes that follow it.
struct ShapedEvent {
    double onset = 0.0;              // seconds
    int pieces = 0;                  // its straight pieces on the grid, each a note or two
    double worst_level_error = 0.0;  // 0..1: how far a level moved to reach a number
    int early_ramps = 0;             // ramps that reach their level a 32nd early
};

// Sound events in seconds (AHAP, Android) placed on the score's grid.
struct GridPlacement {
    double tempo = 1.0;  // seconds per quarter note that fit the events' times
    std::vector<GridNote> notes;
    std::int64_t total_ticks = 0;
    double worst_error = 0.0;         // seconds: how far the furthest time moved to reach the grid
    std::vector<ShapedEvent> shaped;  // for the importer to say what it approximated
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
//   the next note);
// - an event whose strength bends (strength_points) becomes several tied notes whose hairpins
//   and glides follow the bends (envelope_notes.hpp); the bends do not choose the tempo, each
//   lands on the nearest 32nd of the tempo its event's times choose; the number is the nearest to
//   the note's own strength.
// `total` is the piece's length in seconds (rests at its end included), 0 for "the last note".
GridPlacement place_on_grid(std::vector<SoundEvent> events, double total, const Clef& clef,
                            const StringOf& string_of,
                            std::optional<double> tempo_hint = std::nullopt);

// What an importer says about an event it shaped: "the event at 0.3 s: its intensity curve, in
// 2 straight pieces, is tied notes with glides and hairpins; levels to the nearest numbers (at
// most 0.04 of full off)".
std::string shape_note(const ShapedEvent& shaped, const std::string& curve);

// Pitches (any scale: semitones, log frequency) to strings, keeping the melody's contour: up to
// `strings` distinct pitches each get their own string, spread over the staff from string 1;
// more are divided into `strings` equal bands between the lowest and highest.
std::vector<int> strings_by_contour(const std::vector<double>& pitches, int strings);

// The string of a sine clef whose frequency is nearest (in pitch, i.e. by ratio) to `frequency`.
int nearest_string(const Clef& clef, double frequency);

}  // namespace vibscore::formats
