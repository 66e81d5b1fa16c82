#include "bench/feel_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace vibscore::bench {

namespace {

std::size_t index_at(double t, double rate_hz, std::size_t size) {
    const auto k = static_cast<std::ptrdiff_t>(std::ceil(t * rate_hz - 1e-9));
    return static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(k, 0, static_cast<std::ptrdiff_t>(size)));
}

}  // namespace

std::vector<NoteSpan> note_spans(const render::Performance& performance, double scale) {
    std::vector<NoteSpan> spans;
    const auto& tones = performance.tones();
    for (std::size_t i = 0; i < tones.size(); ++i) {
        const auto& tone = tones[i];
        NoteSpan span;
        span.onset = tone.onset;
        span.end = tone.end();
        // A shape clef's waveform scales the number; the benchmark's clefs are sine clefs.
        span.peak = std::max(std::abs(tone.amplitude_start), std::abs(tone.amplitude_end)) * scale;
        span.tied_to_next = i + 1 < tones.size() && tones[i + 1].onset <= tone.end() + 1e-9;
        spans.push_back(span);
    }
    return spans;
}

double median(std::vector<double> values) {
    if (values.empty()) {
        return NAN;
    }
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

Pooled pool(const std::vector<ScoreFeel>& scores) {
    Pooled pooled;
    std::vector<double> onsets, stops, errors;
    for (const ScoreFeel& score : scores) {
        pooled.notes += score.notes;
        pooled.reached += score.reached;
        pooled.silences += score.silences;
        pooled.felt += score.felt;
        onsets.insert(onsets.end(), score.onsets_ms.begin(), score.onsets_ms.end());
        stops.insert(stops.end(), score.stops_ms.begin(), score.stops_ms.end());
        errors.push_back(score.envelope_error);
        pooled.rebound = std::max(pooled.rebound, score.max_rebound);
        pooled.overshoot = std::max(pooled.overshoot, score.max_overshoot);
    }
    pooled.onset_ms = median(onsets);
    pooled.stop_ms = median(stops);
    pooled.error = median(errors);
    return pooled;
}

ScoreFeel measure(const std::string& name, const std::vector<NoteSpan>& notes,
                  const std::vector<double>& written, const std::vector<double>& produced,
                  const std::function<std::vector<double>(double)>& produced_until,
                  double rate_hz) {
    ScoreFeel feel;
    feel.name = name;
    feel.notes = static_cast<int>(notes.size());
    const std::size_t size = std::min(written.size(), produced.size());
    double difference = 0.0, total = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
        difference += std::abs(produced[k] - written[k]);
        total += written[k];
    }
    feel.envelope_error = total > 0.0 ? difference / total : 0.0;

    for (std::size_t i = 0; i < notes.size(); ++i) {
        const NoteSpan& note = notes[i];
        const std::size_t from = index_at(note.onset, rate_hz, size);
        const std::size_t to = index_at(note.end, rate_hz, size);
        double onset = INFINITY;
        for (std::size_t k = from; k < to; ++k) {
            if (produced[k] >= 0.9 * note.peak) {
                onset = (static_cast<double>(k) / rate_hz - note.onset) * 1000.0;
                break;
            }
        }
        feel.onsets_ms.push_back(onset);
        feel.reached += std::isfinite(onset) ? 1 : 0;
        if (from < to && note.peak > 0.0 && produced[from] <= note.peak) {
            const double highest =
                *std::max_element(produced.begin() + static_cast<std::ptrdiff_t>(from),
                                  produced.begin() + static_cast<std::ptrdiff_t>(to));
            feel.max_overshoot = std::max(feel.max_overshoot, highest / note.peak - 1.0);
        }

        if (note.tied_to_next) {
            continue;
        }
        const bool last = i + 1 == notes.size();
        const auto alone = last ? produced : produced_until(notes[i + 1].onset);
        double stop = INFINITY;
        const std::size_t alone_size = std::min(size, alone.size());
        std::size_t stopped = alone_size;
        for (std::size_t k = to; k < alone_size; ++k) {
            if (alone[k] < 0.1 * note.peak) {
                stop = (static_cast<double>(k) / rate_hz - note.end) * 1000.0;
                stopped = k;
                break;
            }
        }
        feel.stops_ms.push_back(std::max(0.0, stop));
        for (std::size_t k = stopped; k < alone_size && note.peak > 0.0; ++k) {
            feel.max_rebound = std::max(feel.max_rebound, alone[k] / note.peak);
        }

        if (last) {
            continue;
        }
        // The silence before the next note: felt when the strength between the two notes' peaks
        // falls to half the weaker one.
        const NoteSpan& next = notes[i + 1];
        ++feel.silences;
        const auto peak_in = [&](std::size_t a, std::size_t b) {
            std::size_t best = a;
            for (std::size_t k = a; k < b && k < size; ++k) {
                if (produced[k] > produced[best]) {
                    best = k;
                }
            }
            return best;
        };
        const std::size_t first_peak = peak_in(from, index_at(next.onset, rate_hz, size));
        const std::size_t second_peak = peak_in(
            index_at(next.onset, rate_hz, size),
            std::max(index_at(next.end, rate_hz, size), index_at(next.onset, rate_hz, size) + 1));
        double valley = INFINITY;
        for (std::size_t k = first_peak; k <= second_peak && k < size; ++k) {
            valley = std::min(valley, produced[k]);
        }
        const double weaker = std::min(produced[first_peak], produced[second_peak]);
        feel.felt += valley <= 0.5 * weaker ? 1 : 0;
    }
    return feel;
}

}  // namespace vibscore::bench
