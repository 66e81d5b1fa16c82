#pragma once

#include <cstddef>
#include <vector>

#include "daemon/render/waveform.hpp"
#include "score/bundle.hpp"

namespace vibscore::render {

// Choices the thesis leaves open; docs/score-format.md explains the defaults.
struct RenderOptions {
    // Silence cut from the end of a note that is directly followed by another note it is not
    // tied to: min(separation_s, separation_max_fraction x the note's written length).
    double separation_s = 0.030;
    double separation_max_fraction = 0.25;
    // First bar to play (0-based); earlier bars are skipped, time starts at this bar.
    std::size_t start_bar = 0;
};

// One sounding note: where it sits in time and how its signal is made.
struct Tone {
    enum class Kind { sine, shape };

    std::size_t bar = 0, symbol = 0;  // in the score
    double onset = 0.0;               // seconds from the start of the performance
    double duration = 0.0;            // sounding time; the rest of its length is silence
    // Strength moves linearly from amplitude_start to amplitude_end across the duration
    // (crescendo, decrescendo, portamento); constant otherwise.
    double amplitude_start = 0.0, amplitude_end = 0.0;

    Kind kind = Kind::sine;
    // sine: frequency glides geometrically from frequency_start to frequency_end (portamento).
    double frequency_start = 0.0, frequency_end = 0.0;
    double phase_cycles = 0.0;  // phase at onset, in cycles (0..1)
    // shape: the clef string's waveform repeats every tempo seconds from the onset; with a
    // portamento it cross-fades into shape_to.
    int shape = -1, shape_to = -1;
    double tempo = 1.0;

    double end() const { return onset + duration; }
};

// A note or rest of the score and the time it takes.
struct SymbolTiming {
    std::size_t bar = 0, symbol = 0;
    double onset = 0.0, length = 0.0;
    bool is_note = false;
};

// A score performed through its clefs: the exact drive signal y(t) in clef units, and for
// actuators without waveform control its amplitude envelope.
class Performance {
  public:
    Performance(const ScoreBundle& bundle, const RenderOptions& options = {});

    double duration() const { return duration_; }
    const std::vector<Tone>& tones() const { return tones_; }
    const std::vector<SymbolTiming>& timeline() const { return timeline_; }
    const Waveform& waveform(int index) const { return waveforms_.at(static_cast<size_t>(index)); }

    // The signal at time t (seconds); 0 outside every tone.
    double value_at(double t) const;
    // The strength at time t: a sine tone's amplitude, or |y| for a shape tone, whose waveform
    // already is the drive level.
    double envelope_at(double t) const;
    // The largest |y| any tone can reach, for scaling to an actuator's range.
    double peak_amplitude() const { return peak_; }

    // Index of the tone sounding at t, or of the last one before it; -1 if none started yet.
    std::ptrdiff_t tone_index_at(double t) const;
    // The tone sounding at t, or nullptr in silence.
    const Tone* tone_sounding_at(double t) const;

    // Phase (in cycles, unreduced) of a sine tone at local time dt since its onset.
    static double sine_cycles(const Tone& tone, double dt);
    // Amplitude of a tone at local time dt.
    static double amplitude(const Tone& tone, double dt);
    // Where evaluation of a shape tone got to, so sample-by-sample rendering need not search.
    struct ShapeCursor {
        std::size_t from = 0, to = 0;
    };
    // Level (before amplitude) of a shape tone at local time dt.
    double shape_level(const Tone& tone, double dt, ShapeCursor& cursor) const;

  private:
    std::vector<Tone> tones_;
    std::vector<SymbolTiming> timeline_;
    std::vector<Waveform> waveforms_;
    std::vector<double> waveform_peaks_;  // largest |level| of each waveform
    double duration_ = 0.0;
    double peak_ = 0.0;
};

}  // namespace vibscore::render
