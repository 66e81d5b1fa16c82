#include "daemon/render/cue_adaptation.hpp"

#include <algorithm>
#include <cmath>

namespace vibscore::render {

namespace {

constexpr double kTimeEpsilon = 1e-9;
constexpr double kAmplitudeEpsilon = 1e-6;

bool is_drive(const Cue& cue) {
    return cue.kind == Cue::Kind::drive;
}

Cue drive_at(double at, double amplitude, double frequency_hz) {
    Cue cue;
    cue.at = at;
    cue.amplitude = amplitude;
    cue.frequency_hz = frequency_hz;
    return cue;
}

// Drives that say the same as the one before them are left out.
std::vector<Cue> without_repeats(const std::vector<Cue>& drives) {
    std::vector<Cue> kept;
    for (const Cue& cue : drives) {
        if (!kept.empty() && kept.back().amplitude == cue.amplitude &&
            kept.back().frequency_hz == cue.frequency_hz && kept.back().ramp_s == 0.0 &&
            cue.ramp_s == 0.0) {
            continue;
        }
        // Two drives at one instant: only the later one is ever felt.
        if (!kept.empty() && std::abs(kept.back().at - cue.at) < kTimeEpsilon) {
            kept.back() = cue;
            continue;
        }
        kept.push_back(cue);
    }
    return kept;
}

std::vector<Cue> pulse_modulated(const std::vector<Cue>& drives, double duration_s,
                                 const CueAdaptation& adaptation) {
    std::vector<Cue> pulses;
    const double period = adaptation.pulse_period_s;
    for (std::size_t i = 0; i < drives.size(); ++i) {
        const double strength = std::clamp(drives[i].amplitude * adaptation.scale, 0.0, 1.0);
        if (strength == 0.0) {
            pulses.push_back(drive_at(drives[i].at, 0.0, 0.0));
            continue;
        }
        // A vibrating stretch: from here until the next drive of 0 (or the end of the pass).
        std::size_t end = i;
        while (end < drives.size() && drives[end].amplitude * adaptation.scale > 0.0) {
            ++end;
        }
        const double stretch_end = end < drives.size() ? drives[end].at : duration_s;
        std::size_t level = i;
        const double stretch_start = drives[i].at;
        for (std::size_t n = 0;; ++n) {
            // Periods are counted from the stretch's start so rounding never accumulates.
            const double start = stretch_start + static_cast<double>(n) * period;
            if (start >= stretch_end - kTimeEpsilon) {
                break;
            }
            while (level + 1 < end && drives[level + 1].at <= start + kTimeEpsilon) {
                ++level;
            }
            const double s = std::clamp(drives[level].amplitude * adaptation.scale, 0.0, 1.0);
            const double frequency = drives[level].frequency_hz;
            if (s >= 1.0 - kTimeEpsilon) {
                pulses.push_back(drive_at(start, 1.0, frequency));
                continue;
            }
            const double on_s = std::min(s * period, stretch_end - start);
            if (on_s < adaptation.min_pulse_s) {
                pulses.push_back(drive_at(start, 0.0, 0.0));
                continue;
            }
            pulses.push_back(drive_at(start, 1.0, frequency));
            pulses.push_back(drive_at(start + on_s, 0.0, 0.0));
        }
        pulses.push_back(drive_at(stretch_end, 0.0, 0.0));
        i = end == drives.size() ? end : end - 1;
    }
    return without_repeats(pulses);
}

// The steps cue_schedule makes along a ramp are update_interval_s apart; three or more that
// keep one frequency and lie on one line are a linear ramp.
std::vector<Cue> with_envelopes(const std::vector<Cue>& drives, const CueAdaptation& adaptation) {
    std::vector<Cue> merged;
    std::size_t i = 0;
    while (i < drives.size()) {
        std::size_t last = i;
        if (i + 1 < drives.size() && drives[i].amplitude > 0.0) {
            const double slope =
                (drives[i + 1].amplitude - drives[i].amplitude) / (drives[i + 1].at - drives[i].at);
            while (last + 1 < drives.size()) {
                const Cue& next = drives[last + 1];
                const bool close =
                    next.at - drives[last].at <= adaptation.update_interval_s + kTimeEpsilon;
                const double predicted = drives[i].amplitude + slope * (next.at - drives[i].at);
                if (!close || next.frequency_hz != drives[i].frequency_hz ||
                    next.amplitude <= 0.0 ||
                    std::abs(next.amplitude - predicted) > kAmplitudeEpsilon) {
                    break;
                }
                ++last;
            }
        }
        Cue cue = drives[i];
        if (last >= i + 2) {
            cue.ramp_to = drives[last].amplitude;
            cue.ramp_s = drives[last].at - drives[i].at;
            merged.push_back(cue);
            i = last;  // the ramp's end holds its strength until the next drive
            continue;
        }
        merged.push_back(cue);
        ++i;
    }
    return merged;
}

}  // namespace

std::vector<Cue> adapt_cues(const std::vector<Cue>& cues, double duration_s,
                            const CueAdaptation& adaptation) {
    std::vector<Cue> drives, positions;
    for (const Cue& cue : cues) {
        (is_drive(cue) ? drives : positions).push_back(cue);
    }
    if (!adaptation.frequency) {
        for (Cue& cue : drives) {
            cue.frequency_hz = 0.0;
        }
    }
    if (!adaptation.amplitude) {
        drives = pulse_modulated(drives, duration_s, adaptation);
    } else if (adaptation.envelopes) {
        drives = with_envelopes(without_repeats(drives), adaptation);
    } else {
        drives = without_repeats(drives);
    }
    std::vector<Cue> adapted = std::move(drives);
    adapted.insert(adapted.end(), positions.begin(), positions.end());
    std::stable_sort(adapted.begin(), adapted.end(), [](const Cue& a, const Cue& b) {
        if (a.at != b.at) {
            return a.at < b.at;
        }
        return is_drive(a) && !is_drive(b);
    });
    return adapted;
}

}  // namespace vibscore::render
