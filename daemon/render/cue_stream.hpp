#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

namespace vibscore::render {

// One thing the player does at one instant of a performance.
struct Cue {
    enum class Kind { drive, position };

    double at = 0.0;  // seconds from the start of the performance
    Kind kind = Kind::drive;
    // drive: from now on vibrate this strongly (clef units, >= 0) at this frequency (0 for
    // curve and line clefs, whose waveform already is the drive level).
    double amplitude = 0.0;
    double frequency_hz = 0.0;
    // drive, only after adaptation for backends with envelopes: the strength moves linearly
    // to ramp_to over ramp_s seconds (0: no ramp) and holds there until the next drive.
    double ramp_to = 0.0;
    double ramp_s = 0.0;
    // drive, as scheduled: the first of a written note (tied to the one before or not), from
    // which on that note's strength is what its end is judged against (a glide's or a legato
    // line's last note is felt as itself, not as the strongest before it).
    bool starts_note = false;
    // position: the note or rest that begins now.
    std::size_t bar = 0, symbol = 0;
};

// A drive cue: from `at` on, this strength at this frequency.
inline Cue drive_at(double at, double amplitude, double frequency_hz) {
    Cue cue;
    cue.at = at;
    cue.amplitude = amplitude;
    cue.frequency_hz = frequency_hz;
    return cue;
}

// Cues in time order, made one at a time as they are asked for, so that what a playback holds
// does not grow with the length of its score.
class CueStream {
  public:
    virtual ~CueStream() = default;
    // The next cue; nullopt once there are no more (and from then on).
    virtual std::optional<Cue> next() = 0;
};

// A stream over cues that are already in a list.
class CueListStream final : public CueStream {
  public:
    explicit CueListStream(std::shared_ptr<const std::vector<Cue>> cues) : cues_(std::move(cues)) {}
    std::optional<Cue> next() override {
        if (index_ == cues_->size()) {
            return std::nullopt;
        }
        return (*cues_)[index_++];
    }

  private:
    std::shared_ptr<const std::vector<Cue>> cues_;
    std::size_t index_ = 0;
};

// Everything a stream has left, in a list: for tests and tools that look at a whole schedule.
std::vector<Cue> collect(CueStream& stream);

// Where a playback's cues come from: a fresh stream for each pass through the score.
class CueSource {
  public:
    virtual ~CueSource() = default;
    virtual std::unique_ptr<CueStream> pass() const = 0;
};

// A source of cues written out in a list.
class CueList final : public CueSource {
  public:
    explicit CueList(std::vector<Cue> cues)
        : cues_(std::make_shared<const std::vector<Cue>>(std::move(cues))) {}
    std::unique_ptr<CueStream> pass() const override {
        return std::make_unique<CueListStream>(cues_);
    }

  private:
    std::shared_ptr<const std::vector<Cue>> cues_;
};

}  // namespace vibscore::render
