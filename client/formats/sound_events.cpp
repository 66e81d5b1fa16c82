#include "client/formats/sound_events.hpp"

#include <algorithm>
#include <cmath>

#include "daemon/render/performance.hpp"
#include "score/limits.hpp"

namespace vibscore::formats {

namespace {

constexpr double kTopPosition = static_cast<double>(limits::strings - 1);

}  // namespace

double strongest_number(const ScoreBundle& bundle) {
    double peak = 0.0;
    for (const auto& bar : bundle.score.bars) {
        for (const double amplitude : bundle.clef_of(bar).numbers) {
            peak = std::max(peak, std::abs(amplitude));
        }
    }
    return peak;
}

double staff_position(int string) {
    return (string - 1) / kTopPosition;
}

int string_at(double position, int strings_in_clef) {
    const int string = 1 + static_cast<int>(std::lround(position * kTopPosition));
    return std::clamp(string, 1, std::max(1, strings_in_clef));
}

SoundTrack sound_track(const ScoreBundle& bundle) {
    const render::Performance performance(bundle);
    SoundTrack track;
    track.title = bundle.score.title;
    track.duration = performance.duration();
    // The piece's one tempo, when it has one, for the formats that can carry it.
    for (std::size_t b = 0; b < bundle.score.bars.size(); ++b) {
        const double tempo = bundle.clef_of(bundle.score.bars[b]).tempo;
        if (b > 0 && tempo != track.tempo) {
            track.tempo = 0.0;
            break;
        }
        track.tempo = tempo;
    }
    const double peak = strongest_number(bundle);
    const auto relative = [&](double amplitude) { return peak > 0.0 ? amplitude / peak : 0.0; };
    const auto& tones = performance.tones();
    for (std::size_t i = 0; i < tones.size(); ++i) {
        const auto& tone = tones[i];
        const Bar& bar = bundle.score.bars[tone.bar];
        const auto& note = std::get<Note>(bar.symbols[tone.symbol]);
        const Clef& clef = bundle.clef_of(bar);
        SoundEvent event;
        event.onset = tone.onset;
        event.duration = tone.duration;
        event.strength = relative(clef.numbers.at(static_cast<std::size_t>(note.number - 1)));
        event.strength_start = relative(tone.amplitude_start);
        event.strength_end = relative(tone.amplitude_end);
        event.pitch_start = event.pitch_end = staff_position(note.string);
        const bool glides = tone.kind == render::Tone::Kind::sine
                                ? tone.frequency_end != tone.frequency_start
                                : tone.shape_to >= 0;
        if (glides && i + 1 < tones.size()) {
            const auto& next = tones[i + 1];
            event.pitch_end = staff_position(
                std::get<Note>(bundle.score.bars[next.bar].symbols[next.symbol]).string);
        }
        if (tone.kind == render::Tone::Kind::sine) {
            event.frequency_start = tone.frequency_start;
            event.frequency_end = tone.frequency_end;
        }
        track.events.push_back(event);
    }
    return track;
}

}  // namespace vibscore::formats
