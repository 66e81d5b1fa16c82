#include "daemon/render/performance.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace vibscore::render {

namespace {

// A note or rest in playing order, with its place in the score and in time.
struct Timing {
    const Note* note = nullptr;  // nullptr for a rest
    const Clef* clef = nullptr;
    std::size_t bar = 0, symbol = 0;
    double onset = 0.0, length = 0.0;
};

bool tied(const Note& a, const Note& b) {
    return (a.legato != 0 && a.legato == b.legato) ||
           (a.portamento != 0 && a.portamento == b.portamento);
}

bool portamento(const Note& a, const Note& b) {
    return a.portamento != 0 && a.portamento == b.portamento;
}

double number_amplitude(const Timing& timing) {
    return timing.clef->numbers.at(static_cast<std::size_t>(timing.note->number - 1));
}

double frequency(const Timing& timing) {
    return timing.clef->strings.at(static_cast<std::size_t>(timing.note->string - 1)).frequency;
}

double fraction(double x) {
    return x - std::floor(x);
}

}  // namespace

Performance::Performance(const ScoreBundle& bundle, const RenderOptions& options) {
    std::vector<Timing> timings;
    // Beats are multiples of 1/8, exact in binary; counting them and multiplying by the tempo
    // once keeps a long piece's onsets free of accumulated rounding.
    double run_start = 0.0;  // seconds where the current tempo began
    double run_beats = 0.0;  // beats since then
    double run_tempo = 0.0;
    const auto now = [&] { return run_start + run_beats * run_tempo; };
    for (std::size_t b = options.start_bar; b < bundle.score.bars.size(); ++b) {
        const Bar& bar = bundle.score.bars[b];
        const Clef& clef = bundle.clef_of(bar);
        if (clef.tempo != run_tempo) {
            run_start = now();
            run_beats = 0.0;
            run_tempo = clef.tempo;
        }
        for (std::size_t s = 0; s < bar.symbols.size(); ++s) {
            const auto& symbol = bar.symbols[s];
            double symbol_beats = 0.0;
            if (const auto* note = std::get_if<Note>(&symbol)) {
                symbol_beats = beats(note->length);
            } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
                symbol_beats = beats(rest->length);
            } else {
                continue;  // a Blank takes no time
            }
            const double onset = now();
            run_beats += symbol_beats;
            Timing timing{std::get_if<Note>(&symbol), &clef, b, s, onset, now() - onset};
            timeline_.push_back({b, s, onset, timing.length, timing.note != nullptr});
            timings.push_back(timing);
        }
    }
    duration_ = now();

    std::map<std::pair<const Clef*, int>, int> shape_of_string;
    const auto shape_index = [&](const Timing& timing) {
        const auto key = std::make_pair(timing.clef, timing.note->string);
        const auto found = shape_of_string.find(key);
        if (found != shape_of_string.end()) {
            return found->second;
        }
        const auto& points =
            timing.clef->strings.at(static_cast<std::size_t>(key.second - 1)).points;
        const Waveform& added = waveforms_.emplace_back(timing.clef->type, points);
        // A Catmull-Rom spline can overshoot its points; find the true peak by sampling.
        double peak = 0.0;
        for (int k = 0; k <= 4096; ++k) {
            peak = std::max(peak, std::abs(added.level(k / 4096.0)));
        }
        waveform_peaks_.push_back(peak);
        const int index = static_cast<int>(waveforms_.size() - 1);
        shape_of_string.emplace(key, index);
        return index;
    };

    for (std::size_t i = 0; i < timings.size(); ++i) {
        const Timing& timing = timings[i];
        if (timing.note == nullptr) {
            continue;
        }
        const Note& note = *timing.note;
        const Timing* previous =
            i > 0 && timings[i - 1].note != nullptr ? &timings[i - 1] : nullptr;
        const Timing* next =
            i + 1 < timings.size() && timings[i + 1].note != nullptr ? &timings[i + 1] : nullptr;
        const bool tied_to_next = next != nullptr && tied(note, *next->note);
        const bool tied_from_previous = previous != nullptr && tied(*previous->note, note);
        const bool glide = next != nullptr && portamento(note, *next->note);

        Tone tone;
        tone.bar = timing.bar;
        tone.symbol = timing.symbol;
        tone.onset = timing.onset;
        const double gap =
            next != nullptr && !tied_to_next
                ? std::min(options.separation_s, options.separation_max_fraction * timing.length)
                : 0.0;
        tone.duration = timing.length - gap;

        const double strength = number_amplitude(timing);
        tone.amplitude_start = tone.amplitude_end = strength;
        if (note.dynamics == Dynamics::crescendo) {
            const bool continues = previous != nullptr && previous->note->dynamics == note.dynamics;
            tone.amplitude_start = continues ? number_amplitude(*previous) : 0.0;
        } else if (note.dynamics == Dynamics::decrescendo) {
            const bool continues = next != nullptr && next->note->dynamics == note.dynamics;
            tone.amplitude_end = continues ? number_amplitude(*next) : 0.0;
        } else if (glide) {
            tone.amplitude_end = number_amplitude(*next);
        }

        tone.tempo = timing.clef->tempo;
        const bool next_same_kind = next != nullptr && (next->clef->type == ClefType::sine) ==
                                                           (timing.clef->type == ClefType::sine);
        if (timing.clef->type == ClefType::sine) {
            tone.kind = Tone::Kind::sine;
            tone.frequency_start = tone.frequency_end = frequency(timing);
            if (glide && next_same_kind) {
                tone.frequency_end = frequency(*next);
            }
            if (tied_from_previous && !tones_.empty() && tones_.back().kind == Tone::Kind::sine) {
                const Tone& before = tones_.back();
                tone.phase_cycles =
                    fraction(before.phase_cycles + sine_cycles(before, before.duration));
            }
        } else {
            tone.kind = Tone::Kind::shape;
            tone.shape = shape_index(timing);
            if (glide && next_same_kind) {
                tone.shape_to = shape_index(*next);
            }
        }
        tones_.push_back(tone);
    }

    for (const Tone& tone : tones_) {
        double level = 1.0;
        if (tone.kind == Tone::Kind::shape) {
            // A cross-fade never leaves the larger of its two waveforms' peaks.
            const auto peak_of = [&](int shape) {
                return shape < 0 ? 0.0 : waveform_peaks_[static_cast<std::size_t>(shape)];
            };
            level = std::max(peak_of(tone.shape), peak_of(tone.shape_to));
        }
        peak_ = std::max(
            peak_, level * std::max(std::abs(tone.amplitude_start), std::abs(tone.amplitude_end)));
    }
}

double Performance::sine_cycles(const Tone& tone, double dt) {
    if (tone.frequency_end == tone.frequency_start) {
        return tone.frequency_start * dt;
    }
    // Geometric glide f(t) = f0 * r^(t/T); its integral gives the phase.
    const double ratio = tone.frequency_end / tone.frequency_start;
    const double u = dt / tone.duration;
    return tone.frequency_start * tone.duration * (std::pow(ratio, u) - 1.0) / std::log(ratio);
}

double Performance::amplitude(const Tone& tone, double dt) {
    if (tone.amplitude_end == tone.amplitude_start) {
        return tone.amplitude_start;
    }
    return tone.amplitude_start +
           (tone.amplitude_end - tone.amplitude_start) * (dt / tone.duration);
}

double Performance::shape_level(const Tone& tone, double dt, ShapeCursor& cursor) const {
    const double tau = fraction(dt / tone.tempo);
    const double level = waveform(tone.shape).level(tau, cursor.from);
    if (tone.shape_to < 0) {
        return level;
    }
    const double u = dt / tone.duration;
    return level + (waveform(tone.shape_to).level(tau, cursor.to) - level) * u;
}

std::ptrdiff_t Performance::tone_index_at(double t) const {
    const auto after =
        std::upper_bound(tones_.begin(), tones_.end(), t,
                         [](double time, const Tone& tone) { return time < tone.onset; });
    return (after - tones_.begin()) - 1;
}

const Tone* Performance::tone_sounding_at(double t) const {
    const auto index = tone_index_at(t);
    if (index < 0 || t >= tones_[static_cast<std::size_t>(index)].end()) {
        return nullptr;
    }
    return &tones_[static_cast<std::size_t>(index)];
}

double Performance::value_at(double t) const {
    const Tone* tone = tone_sounding_at(t);
    if (tone == nullptr) {
        return 0.0;
    }
    const double dt = t - tone->onset;
    if (tone->kind == Tone::Kind::sine) {
        const double cycles = fraction(tone->phase_cycles + sine_cycles(*tone, dt));
        return amplitude(*tone, dt) * std::sin(2.0 * M_PI * cycles);
    }
    ShapeCursor cursor;
    return amplitude(*tone, dt) * shape_level(*tone, dt, cursor);
}

double Performance::envelope_at(double t) const {
    const Tone* tone = tone_sounding_at(t);
    if (tone == nullptr) {
        return 0.0;
    }
    const double dt = t - tone->onset;
    if (tone->kind == Tone::Kind::sine) {
        return std::abs(amplitude(*tone, dt));
    }
    ShapeCursor cursor;
    return std::abs(amplitude(*tone, dt) * shape_level(*tone, dt, cursor));
}

}  // namespace vibscore::render
