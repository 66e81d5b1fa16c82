#include "daemon/render/cue_schedule.hpp"

#include <cmath>
#include <utility>

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

}  // namespace

ScheduleStream::Breakpoints::Breakpoints(const Performance& performance, const Tone& tone,
                                         const CueOptions& options)
    : duration_(tone.duration),
      tempo_(tone.tempo),
      step_(options.update_interval_s),
      changing_(changes_within(tone)),
      next_step_(options.update_interval_s) {
    if (tone.kind != Tone::Kind::shape) {
        return;
    }
    // Exact steps of square waves and corners of line shapes, in every repetition.
    for (const int shape : {tone.shape, tone.shape_to}) {
        if (shape >= 0) {
            shapes_.push_back({&performance.waveform(shape).point_times(), 0.0, 0});
        }
    }
}

std::optional<double> ScheduleStream::Breakpoints::peek(const ShapePoints& points) const {
    if (points.times->empty() || points.repeat >= duration_) {
        return std::nullopt;
    }
    // Points come in time order within a repetition and repetitions follow one another, so the
    // first one past the tone's end is the end of this shape's points.
    const double dt = points.repeat + (*points.times)[points.index] * tempo_;
    return dt < duration_ ? std::optional(dt) : std::nullopt;
}

std::optional<double> ScheduleStream::Breakpoints::next() {
    if (!onset_given_) {
        onset_given_ = true;
        last_ = 0.0;
        return 0.0;
    }
    if (!changing_) {
        return std::nullopt;
    }
    while (true) {
        std::optional<double> earliest;
        ShapePoints* from = nullptr;
        if (next_step_ < duration_) {
            earliest = next_step_;
        }
        for (auto& shape : shapes_) {
            const auto at = peek(shape);
            if (at && (!earliest || *at < *earliest)) {
                earliest = at;
                from = &shape;
            }
        }
        if (!earliest) {
            return std::nullopt;
        }
        if (from == nullptr) {
            next_step_ += step_;
        } else if (++from->index == from->times->size()) {
            from->index = 0;
            from->repeat += tempo_;
        }
        if (*earliest == *last_) {
            continue;  // a point on an update step, or on the other shape's point
        }
        last_ = earliest;
        return earliest;
    }
}

ScheduleStream::ScheduleStream(std::shared_ptr<const Performance> performance,
                               const CueOptions& options)
    : performance_(std::move(performance)), options_(options) {}

std::optional<Cue> ScheduleStream::tone_drive() {
    const auto& tones = performance_->tones();
    while (tone_ < tones.size()) {
        const Tone& tone = tones[tone_];
        if (!in_tone_) {
            breakpoints_ = Breakpoints(*performance_, tone, options_);
            cursor_ = {};
            in_tone_ = true;
        }
        if (const auto dt = breakpoints_.next()) {
            const double amplitude = Performance::amplitude(tone, *dt);
            Cue drive =
                tone.kind == Tone::Kind::sine
                    ? drive_at(tone.onset + *dt, std::abs(amplitude),
                               instantaneous_frequency(tone, *dt))
                    : drive_at(tone.onset + *dt,
                               std::abs(amplitude * performance_->shape_level(tone, *dt, cursor_)),
                               0.0);
            drive.starts_note = *dt == 0.0;
            return drive;
        }
        in_tone_ = false;
        ++tone_;
        const bool next_starts_now = tone_ < tones.size() && tones[tone_].onset <= tone.end();
        if (!next_starts_now) {
            return drive_at(tone.end(), 0.0, 0.0);
        }
    }
    return std::nullopt;
}

std::optional<Cue> ScheduleStream::next_drive() {
    while (auto cue = tone_drive()) {
        if (last_drive_ && last_drive_->amplitude == cue->amplitude &&
            last_drive_->frequency_hz == cue->frequency_hz) {
            continue;
        }
        last_drive_ = cue;
        return cue;
    }
    return std::nullopt;
}

std::optional<Cue> ScheduleStream::next() {
    if (!waiting_drive_) {
        waiting_drive_ = next_drive();
    }
    const auto& timeline = performance_->timeline();
    // A drive at a note's onset goes first: the actuator is what people feel.
    if (timing_ < timeline.size() &&
        (!waiting_drive_ || waiting_drive_->at > timeline[timing_].onset)) {
        const auto& timing = timeline[timing_++];
        Cue position;
        position.at = timing.onset;
        position.kind = Cue::Kind::position;
        position.bar = timing.bar;
        position.symbol = timing.symbol;
        return position;
    }
    return std::exchange(waiting_drive_, std::nullopt);
}

std::vector<Cue> cue_schedule(const Performance& performance, const CueOptions& options) {
    // The stream only reads the performance; it does not outlive this call.
    ScheduleStream stream(std::shared_ptr<const Performance>(std::shared_ptr<void>(), &performance),
                          options);
    return collect(stream);
}

}  // namespace vibscore::render
