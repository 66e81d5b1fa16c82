#include "daemon/render/cue_adaptation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vibscore::render {

namespace {

constexpr double kTimeEpsilon = 1e-9;
constexpr double kAmplitudeEpsilon = 1e-6;
// The most input drives read ahead of the one being planned: a hairpin's steps come every
// update interval, and what lies further than the planner looks ahead is not read early.
constexpr std::size_t kMostAhead = 4096;

using Stage = AdaptedCueStream::Stage;

// Drives that say the same as the one before them are left out; of two drives at one instant
// only the later one is ever felt. A drive goes on once the one after it is known.
class WithoutRepeats final : public Stage {
  public:
    explicit WithoutRepeats(Stage& input) : input_(input) {}
    std::optional<Cue> next() override {
        while (auto cue = input_.next()) {
            if (!kept_) {
                kept_ = cue;
                continue;
            }
            if (kept_->amplitude == cue->amplitude && kept_->frequency_hz == cue->frequency_hz &&
                kept_->ramp_s == 0.0 && cue->ramp_s == 0.0) {
                continue;
            }
            if (std::abs(kept_->at - cue->at) < kTimeEpsilon) {
                kept_ = cue;
                continue;
            }
            return std::exchange(kept_, cue);
        }
        return std::exchange(kept_, std::nullopt);
    }

  private:
    Stage& input_;
    std::optional<Cue> kept_;
};

// A stage that makes its cues a few at a time: step() adds what the input read so far makes to
// made_, and says false once the input is exhausted.
class BatchingStage : public Stage {
  public:
    std::optional<Cue> next() final {
        while (made_.empty()) {
            if (!step()) {
                return std::nullopt;
            }
        }
        const Cue cue = made_.front();
        made_.pop_front();
        return cue;
    }

  protected:
    virtual bool step() = 0;

    std::deque<Cue> made_;
};

// Strength as pulse width (CueAdaptation::amplitude). A vibrating stretch runs from a drive
// above 0 to the next drive of 0 (or the end of the pass); its periods are counted from its
// start, so rounding never accumulates. Each period needs the drives up to its end read.
class PulseModulation final : public BatchingStage {
  public:
    PulseModulation(Stage& input, double duration_s, const CueAdaptation& adaptation)
        : input_(input), duration_s_(duration_s), adaptation_(adaptation) {}

  private:
    bool vibrates(const Cue& cue) const { return cue.amplitude * adaptation_.scale > 0.0; }
    double strength(const Cue& cue) const {
        return std::clamp(cue.amplitude * adaptation_.scale, 0.0, 1.0);
    }

    // Makes the next cues; false when the input is exhausted.
    bool step() override {
        if (!in_stretch_) {
            auto cue = end_drive_ ? std::exchange(end_drive_, std::nullopt) : input_.next();
            if (!cue) {
                return false;
            }
            if (!vibrates(*cue)) {
                made_.push_back(drive_at(cue->at, 0.0, 0.0));
                return true;
            }
            in_stretch_ = true;
            stretch_start_ = cue->at;
            level_ = *cue;
            periods_ = 0;
            stretch_end_.reset();
            return true;
        }
        const double period = adaptation_.pulse_period_s;
        const double start = stretch_start_ + static_cast<double>(periods_) * period;
        while (!stretch_end_ && (ahead_.empty() || ahead_.back().at <= start + period)) {
            auto cue = input_.next();
            if (!cue) {
                stretch_end_ = duration_s_;
            } else if (!vibrates(*cue)) {
                stretch_end_ = cue->at;
                end_drive_ = cue;  // taken again after the stretch, as any other drive
            } else {
                ahead_.push_back(*cue);
            }
        }
        if (stretch_end_ && start >= *stretch_end_ - kTimeEpsilon) {
            made_.push_back(drive_at(*stretch_end_, 0.0, 0.0));
            in_stretch_ = false;
            ahead_.clear();
            return true;
        }
        while (!ahead_.empty() && ahead_.front().at <= start + kTimeEpsilon) {
            level_ = ahead_.front();
            ahead_.pop_front();
        }
        ++periods_;
        const double s = strength(level_);
        if (s >= 1.0 - kTimeEpsilon) {
            made_.push_back(drive_at(start, 1.0, level_.frequency_hz));
            return true;
        }
        // The stretch's end, when not yet read, lies beyond this period.
        const double on_s = stretch_end_ ? std::min(s * period, *stretch_end_ - start) : s * period;
        if (on_s < adaptation_.min_pulse_s) {
            made_.push_back(drive_at(start, 0.0, 0.0));
            return true;
        }
        made_.push_back(drive_at(start, 1.0, level_.frequency_hz));
        made_.push_back(drive_at(start + on_s, 0.0, 0.0));
        return true;
    }

    Stage& input_;
    double duration_s_;
    CueAdaptation adaptation_;
    bool in_stretch_ = false;
    double stretch_start_ = 0.0;
    std::size_t periods_ = 0;
    Cue level_;                          // the drive in force at the current period's start
    std::deque<Cue> ahead_;              // the stretch's drives read but not yet in force
    std::optional<double> stretch_end_;  // once read
    std::optional<Cue> end_drive_;       // the drive of 0 that ended the stretch
};

// The steps cue_schedule makes along a ramp are update_interval_s apart; three or more that
// keep one frequency and lie on one line are a linear ramp, handed over as one drive. A ramp's
// last step starts the next run, since its strength holds until the next drive.
class Envelopes final : public Stage {
  public:
    Envelopes(Stage& input, const CueAdaptation& adaptation)
        : input_(input), interval_s_(adaptation.update_interval_s) {}

    std::optional<Cue> next() override {
        const auto first = read();
        if (!first || !(first->amplitude > 0.0)) {
            return first;
        }
        const auto second = read();
        if (!second) {
            return first;
        }
        const double slope = (second->amplitude - first->amplitude) / (second->at - first->at);
        Cue last = *first;
        std::size_t steps = 0;
        auto candidate = second;
        while (candidate) {
            const bool close = candidate->at - last.at <= interval_s_ + kTimeEpsilon;
            const double predicted = first->amplitude + slope * (candidate->at - first->at);
            if (!close || candidate->frequency_hz != first->frequency_hz ||
                candidate->amplitude <= 0.0 ||
                std::abs(candidate->amplitude - predicted) > kAmplitudeEpsilon) {
                break;
            }
            last = *candidate;
            ++steps;
            candidate = read();
        }
        if (candidate) {
            unread_.push_front(*candidate);
        }
        if (steps >= 2) {
            unread_.push_front(last);
            Cue ramp = *first;
            ramp.ramp_to = last.amplitude;
            ramp.ramp_s = last.at - first->at;
            return ramp;
        }
        if (steps == 1) {
            unread_.push_front(*second);
        }
        return first;
    }

  private:
    std::optional<Cue> read() {
        if (unread_.empty()) {
            return input_.next();
        }
        const Cue cue = unread_.front();
        unread_.pop_front();
        return cue;
    }

    Stage& input_;
    double interval_s_;
    std::deque<Cue> unread_;  // read ahead and given back: at most two
};

// Strengths become drives of the declared actuator (CueAdaptation::actuator), segment by segment:
// each input drive holds until the next one, and the planner chooses what makes the actuator
// follow that. It reads one drive ahead, to know where a segment ends and whether silence
// follows; the planner's drives lie within the segment, so none precedes a position not yet
// read. Between passes the actuator's state carries over (PassLink); only the last pass drives on
// past its end, to brake after its last note.
class ActuatorDrives final : public BatchingStage {
  public:
    ActuatorDrives(Stage& input, double duration_s, const CueAdaptation& adaptation,
                   const PassLink& link)
        : input_(input),
          duration_s_(duration_s),
          scale_(adaptation.scale),
          link_(link),
          planner_(*adaptation.actuator,
                   {adaptation.scale, adaptation.actuator->compensation,
                    adaptation.reverse && adaptation.actuator->brake == actuator::Brake::reverse,
                    adaptation.min_drive_pulse_s,
                    adaptation.uncertainty.value_or(uncertainty_of(*adaptation.actuator))},
                   link.carry ? *link.carry : PlannerCarry{}) {}

  private:
    bool step() override {
        if (done_) {
            return false;
        }
        std::vector<Cue> made;
        if (!started_) {
            started_ = true;
            read_ahead(0.0);
            // Silence until the first drive: what the previous pass left ringing is stopped.
            const double first = !ahead_.empty() ? ahead_.front().at : end_of_pass();
            planner_.segment(0.0, first, 0.0, 0.0, false, made);
        } else if (!ahead_.empty()) {
            const Cue current = ahead_.front();
            ahead_.pop_front();
            read_ahead(current.at);
            const double until = !ahead_.empty() ? ahead_.front().at : end_of_pass();
            const bool silence_follows = ahead_.empty() || !vibrates(ahead_.front());
            if (current.starts_note) {
                planner_.note_starts();
            }
            planner_.segment(current.at, until, current.amplitude, current.frequency_hz,
                             silence_follows, made,
                             silence_follows || !vibrates(current) ? std::span<const Written>{}
                                                                   : rest_of_note());
        } else {
            done_ = true;
            if (link_.carry && !link_.last) {
                *link_.carry = planner_.carry();
            }
        }
        made_.insert(made_.end(), made.begin(), made.end());
        return true;
    }

    bool vibrates(const Cue& cue) const { return cue.amplitude * scale_ > 0.0; }

    // Reads on until the drive after the one at `from`, and further, as far as the planner looks
    // ahead, while the note goes on (up to the silence that ends it).
    void read_ahead(double from) {
        const double horizon = from + planner_.look_ahead_s();
        while (!input_done_ &&
               (ahead_.empty() || (vibrates(ahead_.back()) && ahead_.back().at < horizon &&
                                   ahead_.size() < kMostAhead))) {
            if (auto cue = input_.next()) {
                ahead_.push_back(*cue);
            } else {
                input_done_ = true;
            }
        }
    }

    // The drives read ahead up to the silence that ends the note, as the planner's segments;
    // empty when that silence has not been read (further than it looks ahead).
    std::span<const Written> rest_of_note() {
        rest_.clear();
        for (std::size_t i = 0; i < ahead_.size(); ++i) {
            if (!vibrates(ahead_[i])) {
                return rest_;
            }
            const double until = i + 1 < ahead_.size() ? ahead_[i + 1].at : end_of_pass();
            rest_.push_back({ahead_[i].at, until, ahead_[i].amplitude, ahead_[i].frequency_hz});
        }
        if (!input_done_) {
            rest_.clear();
        }
        return rest_;
    }

    // Where the last segment ends: the pass's end, unless the last pass brakes on after it.
    double end_of_pass() const { return link_.last ? INFINITY : duration_s_; }

    Stage& input_;
    double duration_s_;
    double scale_;
    PassLink link_;
    DrivePlanner planner_;
    // The input drives read ahead: the next one, and (while a note goes on) as far as the
    // planner looks ahead.
    std::deque<Cue> ahead_;
    std::vector<Written> rest_;  // rest_of_note()'s
    bool input_done_ = false;
    bool started_ = false;
    bool done_ = false;
};

}  // namespace

// The input's drives (without frequency when the actuator has no choice of it); its positions
// are set aside for the adapted stream to merge back in.
class AdaptedCueStream::InputDrives final : public Stage {
  public:
    InputDrives(std::unique_ptr<CueStream> input, bool frequency, std::deque<Cue>& positions)
        : input_(std::move(input)), frequency_(frequency), positions_(positions) {}
    std::optional<Cue> next() override {
        while (auto cue = input_->next()) {
            if (cue->kind != Cue::Kind::drive) {
                positions_.push_back(*cue);
                continue;
            }
            if (!frequency_) {
                cue->frequency_hz = 0.0;
            }
            return cue;
        }
        return std::nullopt;
    }

  private:
    std::unique_ptr<CueStream> input_;
    bool frequency_;
    std::deque<Cue>& positions_;
};

AdaptedCueStream::AdaptedCueStream(std::unique_ptr<CueStream> input, double duration_s,
                                   const CueAdaptation& adaptation, const PassLink& link)
    : input_(std::make_unique<InputDrives>(std::move(input), adaptation.frequency, positions_)) {
    const auto add = [&](std::unique_ptr<Stage> stage) { stages_.push_back(std::move(stage)); };
    const auto last = [&]() -> Stage& {
        return stages_.empty() ? static_cast<Stage&>(*input_) : *stages_.back();
    };
    CueAdaptation after = adaptation;
    if (adaptation.actuator) {
        add(std::make_unique<ActuatorDrives>(last(), duration_s, adaptation, link));
        after.scale = 1.0;  // the drives are final: pulse modulation takes them as they are
    }
    if (!adaptation.amplitude) {
        add(std::make_unique<PulseModulation>(last(), duration_s, after));
        add(std::make_unique<WithoutRepeats>(last()));
    } else if (adaptation.envelopes) {
        add(std::make_unique<WithoutRepeats>(last()));
        add(std::make_unique<Envelopes>(last(), adaptation));
    } else {
        add(std::make_unique<WithoutRepeats>(last()));
    }
}

AdaptedCueStream::~AdaptedCueStream() = default;

std::optional<Cue> AdaptedCueStream::next() {
    // Every stage reads its input to the end before it says it has no more, so once the drives
    // are done every position has been set aside.
    if (!waiting_drive_ && !drives_done_) {
        waiting_drive_ = stages_.back()->next();
        drives_done_ = !waiting_drive_;
    }
    // A position not yet read lies at or after the waiting drive (each stage has read its input
    // up to that drive's time), and at one instant the drive goes first.
    if (!positions_.empty() && (!waiting_drive_ || positions_.front().at < waiting_drive_->at)) {
        const Cue position = positions_.front();
        positions_.pop_front();
        return position;
    }
    return std::exchange(waiting_drive_, std::nullopt);
}

std::vector<Cue> adapt_cues(const std::vector<Cue>& cues, double duration_s,
                            const CueAdaptation& adaptation) {
    AdaptedCueStream stream(
        std::make_unique<CueListStream>(std::make_shared<const std::vector<Cue>>(cues)), duration_s,
        adaptation);
    return collect(stream);
}

}  // namespace vibscore::render
