#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "daemon/render/cue_stream.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::render {

struct CueOptions {
    // Changing strength (crescendo, portamento, curve waveforms) is followed in steps this far
    // apart at most; steps in line waveforms fall exactly on their points.
    double update_interval_s = 0.005;
};

// The performance as actuator commands (no backend takes a sample stream): a drive at each note
// onset, updates along ramps and shapes, a drive of 0 when a note ends, and a position cue at
// each note or rest. Cues are in time order; a drive equal to the one before is left out.
// Each cue is worked out when it is asked for: the stream holds one tone's place, never the
// schedule, so an hour of dense shapes costs no more memory than a second.
class ScheduleStream final : public CueStream {
  public:
    // The stream shares the performance, which lives as long as either.
    explicit ScheduleStream(std::shared_ptr<const Performance> performance,
                            const CueOptions& options = {});
    std::optional<Cue> next() override;

  private:
    // The times within one tone (from its onset) where its drive is worked out: the onset, then
    // for a changing tone every update interval, merged with a shape's points in every
    // repetition of its waveform; in order, each once.
    class Breakpoints {
      public:
        Breakpoints() = default;
        Breakpoints(const Performance& performance, const Tone& tone, const CueOptions& options);
        std::optional<double> next();

      private:
        // One shape's points, repetition after repetition.
        struct ShapePoints {
            const std::vector<double>* times = nullptr;
            double repeat = 0.0;
            std::size_t index = 0;
        };
        std::optional<double> peek(const ShapePoints& points) const;

        double duration_ = 0.0, tempo_ = 1.0, step_ = 0.0;
        bool onset_given_ = false;
        bool changing_ = false;
        double next_step_ = 0.0;
        std::vector<ShapePoints> shapes_;
        std::optional<double> last_;
    };

    // Drives as the tones make them, before equal neighbours are left out.
    std::optional<Cue> tone_drive();
    std::optional<Cue> next_drive();

    std::shared_ptr<const Performance> performance_;
    CueOptions options_;
    std::size_t tone_ = 0;  // the tone whose drives come next
    bool in_tone_ = false;
    Breakpoints breakpoints_;
    Performance::ShapeCursor cursor_;
    std::optional<Cue> last_drive_;     // the last one let through
    std::optional<Cue> waiting_drive_;  // made, not yet handed out
    std::size_t timing_ = 0;            // the next note or rest's position cue
};

// A score's cues: a schedule stream over its performance for each pass.
class ScheduleSource final : public CueSource {
  public:
    ScheduleSource(std::shared_ptr<const Performance> performance, const CueOptions& options = {})
        : performance_(std::move(performance)), options_(options) {}
    std::unique_ptr<CueStream> pass() const override {
        return std::make_unique<ScheduleStream>(performance_, options_);
    }

  private:
    std::shared_ptr<const Performance> performance_;
    CueOptions options_;
};

// The whole schedule in a list (tests, tools and the hil expectations).
std::vector<Cue> cue_schedule(const Performance& performance, const CueOptions& options = {});

}  // namespace vibscore::render
