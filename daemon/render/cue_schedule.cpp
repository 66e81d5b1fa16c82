#include "daemon/render/cue_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace vibscore::render {

namespace {

double instantaneous_frequency(const Tone& tone, double dt) {
    if (tone.frequency_end == tone.frequency_start) {
        return tone.frequency_start;
    }
    return tone.frequency_start *
           std::pow(tone.frequency_end / tone.frequency_start, dt / tone.duration);
}

bool changes_within(const Tone& tone) {
    return tone.amplitude_start != tone.amplitude_end ||
           tone.frequency_start != tone.frequency_end || tone.kind == Tone::Kind::shape;
}

// Local times (from the onset) at which a tone's drive must be recomputed.
std::vector<double> breakpoints(const Performance& performance, const Tone& tone,
                                const CueOptions& options) {
    std::vector<double> times{0.0};
    if (!changes_within(tone)) {
        return times;
    }
    for (double dt = options.update_interval_s; dt < tone.duration;
         dt += options.update_interval_s) {
        times.push_back(dt);
    }
    if (tone.kind == Tone::Kind::shape) {
        // Exact steps of square waves and corners of line shapes, in every repetition.
        for (const int shape : {tone.shape, tone.shape_to}) {
            if (shape < 0) {
                continue;
            }
            for (double repeat = 0.0; repeat < tone.duration; repeat += tone.tempo) {
                for (const double point : performance.waveform(shape).point_times()) {
                    const double dt = repeat + point * tone.tempo;
                    if (dt < tone.duration) {
                        times.push_back(dt);
                    }
                }
            }
        }
        std::sort(times.begin(), times.end());
        times.erase(std::unique(times.begin(), times.end()), times.end());
    }
    return times;
}

}  // namespace

std::vector<Cue> cue_schedule(const Performance& performance, const CueOptions& options) {
    std::vector<Cue> drives;
    const auto& tones = performance.tones();
    const auto push_drive = [&](double at, double amplitude, double frequency) {
        if (!drives.empty() && drives.back().amplitude == amplitude &&
            drives.back().frequency_hz == frequency) {
            return;
        }
        Cue cue;
        cue.at = at;
        cue.amplitude = amplitude;
        cue.frequency_hz = frequency;
        drives.push_back(cue);
    };
    for (std::size_t i = 0; i < tones.size(); ++i) {
        const Tone& tone = tones[i];
        Performance::ShapeCursor cursor;
        for (const double dt : breakpoints(performance, tone, options)) {
            const double amplitude = Performance::amplitude(tone, dt);
            if (tone.kind == Tone::Kind::sine) {
                push_drive(tone.onset + dt, std::abs(amplitude), instantaneous_frequency(tone, dt));
            } else {
                push_drive(tone.onset + dt,
                           std::abs(amplitude * performance.shape_level(tone, dt, cursor)), 0.0);
            }
        }
        const bool next_starts_now = i + 1 < tones.size() && tones[i + 1].onset <= tone.end();
        if (!next_starts_now) {
            push_drive(tone.end(), 0.0, 0.0);
        }
    }

    std::vector<Cue> cues;
    cues.reserve(drives.size() + performance.timeline().size());
    auto drive = drives.begin();
    for (const auto& timing : performance.timeline()) {
        for (; drive != drives.end() && drive->at <= timing.onset; ++drive) {
            cues.push_back(*drive);
        }
        Cue position;
        position.at = timing.onset;
        position.kind = Cue::Kind::position;
        position.bar = timing.bar;
        position.symbol = timing.symbol;
        cues.push_back(position);
    }
    cues.insert(cues.end(), drive, drives.end());
    return cues;
}

}  // namespace vibscore::render
