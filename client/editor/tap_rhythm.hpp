#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "score/score.hpp"

namespace vibscore::editor {

// A rhythm tapped on the buttons, as an iPhone records "Create New Vibration" on its screen: each
// press of Select starts a note, each press of Down a rest. Buttons that report releases (evdev
// keys) end a note where Select is let go: held is a note, released a rest; a terminal sees no
// releases, so there a note lasts until the next tap. A release shorter than
// `kShortestReleasedRest`, or than a quarter of the time to the next tap, is the silence any
// thumb needs between two presses, not a rest.
class TapRecorder {
  public:
    using Time = std::chrono::microseconds;

    static constexpr double kShortestReleasedRest = 0.15;  // seconds

    void press_select(Time at);
    void release_select(Time at);
    void press_rest(Time at);
    // The press that ended tapping: where a terminal's last note or rest ends (no later than
    // the usual (median) time between two taps, so a pause before pressing it does not count).
    void finish(Time at);

    bool empty() const { return taps_.empty(); }
    int notes() const;
    // Notes and rests tapped so far.
    int taps() const { return static_cast<int>(taps_.size()); }

    // Onsets and ends in seconds from the first tap, as a rhythm to quantise.
    struct Sound {
        bool note = true;
        double onset = 0.0;
        double end = 0.0;  // the release, or the next tap
    };
    std::vector<Sound> sounds() const;

    bool operator==(const TapRecorder&) const = default;

  private:
    struct Tap {
        bool note = true;
        Time down{};
        std::optional<Time> up;
        bool operator==(const Tap&) const = default;
    };
    std::vector<Tap> taps_;
    std::optional<Time> finished_;
};

// Tapped sounds placed on the score's grid with the importers' quantisation
// (client/formats/grid_fit.*, score_builder.*): lengths from 32nd to whole, dots, bars of four
// beats. The tempo is chosen to fit: the most common time between taps is a quarter note (as
// the importers choose it), refined to the taps; the bar clef's own `clef_tempo` when that is
// within 5 % of it, so a rhythm tapped at the clef's pace needs no other clef. Each time between
// two taps is read on its own, to the finest length a thumb's ±20 ms can tell at that tempo, so
// the same interval is the same length wherever it falls. Every note sits on `string` with
// `number`; the bars are on `clef_id`, and the caller puts them on a clef of `tempo`.
struct TappedRhythm {
    std::vector<Bar> bars;  // on clef `clef_id`
    double tempo = 0.0;     // seconds per quarter note the taps fit
    int notes = 0;
    int rests = 0;
};
// Throws DocumentError when the rhythm breaks a score's limits.
TappedRhythm tapped_rhythm(const std::vector<TapRecorder::Sound>& sounds, double clef_tempo,
                           const std::string& clef_id, int string, int number);

}  // namespace vibscore::editor
