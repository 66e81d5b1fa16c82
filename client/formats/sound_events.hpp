#pragma once

#include <string>
#include <utility>
#include <vector>

#include "score/bundle.hpp"

namespace vibscore::formats {

// A note as the formats outside vibscore see it: when it sounds and how its strength and pitch
// move while it does. Exports make these from a score's performance; the AHAP and Android
// readers make them from a file, and place_on_grid turns them back into notes.
struct SoundEvent {
    double onset = 0.0;     // seconds from the start
    double duration = 0.0;  // sounding time in seconds; 0 for a tap (an AHAP transient)
    // Strengths are 0..1 of the strongest number in play. `strength` is the note's own number
    // (exports know it; imports infer it); start and end are where its hairpin or glide begins
    // and ends.
    double strength = 0.0;
    double strength_start = 0.0, strength_end = 0.0;
    // The staff position: 0 for string 1 up to 1 for string 6; a glide moves it.
    double pitch_start = 0.0, pitch_end = 0.0;
    // The frequency the clef gives the note, in Hz; 0 on curve and line clefs.
    double frequency_start = 0.0, frequency_end = 0.0;
    // Where the strength bends between start and end (absolute time, strength), in time order:
    // an imported curve that is more than one straight ramp. Empty for a straight one.
    std::vector<std::pair<double, double>> strength_points;

    double end() const { return onset + duration; }
};

struct SoundTrack {
    std::string title;
    std::vector<SoundEvent> events;  // in time order, never overlapping
    double duration = 0.0;           // the whole piece, rests at the end included
    double tempo = 0.0;              // seconds per quarter note when every bar has the same; else 0
};

// Staff position of a string (1..6) and back, the way sharpness and pitch carry strings.
double staff_position(int string);
int string_at(double position, int strings_in_clef);

// The largest amplitude any number has in the clefs the score's bars use: strength 1.
double strongest_number(const ScoreBundle& bundle);

// The score's notes as its clefs sound them (the default silence, hairpins and glides
// included), with strengths relative to the strongest number among the clefs its bars use.
SoundTrack sound_track(const ScoreBundle& bundle);

}  // namespace vibscore::formats
