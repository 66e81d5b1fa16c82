#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "daemon/render/cue_adaptation.hpp"

namespace vibscore::daemon {

// A cue of a playback and the pass through the score it belongs to (0 is the first).
struct PassCue {
    render::Cue cue;
    std::uint64_t pass = 0;
};

// The cues a playback runs: pass after pass of its score (`repeat` more after the first, -1
// without end), each adapted to the actuator, made as playback advances. The player reads a
// few cues ahead (the next drive to prepare, the next switch-off for a kernel timer); nothing
// else is kept, so the memory a playback holds does not grow with its score's length. With a
// declared actuator the passes continue each other (render::PassLink): the actuator's state
// carries over, and only the last pass drives on after its end (braking its last note).
//
// The work a playback may cause is bounded: at most limits::max_playback_cues_per_second cues
// per second of its schedule, with a burst of as many (a token bucket counted in schedule time,
// so a score passes or fails the same way on every run, whatever the load). The cues end before
// the first one over the bound, and end_reason() says why.
class PlaybackCues {
  public:
    PlaybackCues(std::shared_ptr<const render::CueSource> source, double duration_s, int repeat,
                 const render::CueAdaptation& adaptation);

    // The cue `index` places ahead (0: the next one), read as far as needed; nullptr when the
    // playback ends before it. Valid until pop() drops it.
    const PassCue* ahead(std::size_t index);
    // Drops the next cue.
    void pop();

    // Why there are no more cues: "completed", or "limit-exceeded: ..." when the score asked
    // for more cues a second than a playback may run.
    const std::string& end_reason() const { return end_reason_; }

  private:
    // Appends the next cue of the playback to the read-ahead; false when there is none.
    bool read();
    // Takes a cue due at `at_us` of the schedule from the bucket; false when it is empty.
    bool within_rate(std::int64_t at_us);

    std::shared_ptr<const render::CueSource> source_;
    double duration_s_;
    int repeat_;
    render::CueAdaptation adaptation_;
    // Where the declared actuator is when a pass ends, for the next one to go on from.
    std::shared_ptr<render::PlannerCarry> carry_;
    std::unique_ptr<render::CueStream> pass_stream_;
    std::uint64_t pass_ = 0;
    bool pass_had_cues_ = false;
    bool ended_ = false;
    std::deque<PassCue> read_ahead_;
    std::string end_reason_ = "completed";
    // The bucket: microseconds of schedule time saved up (a cue costs 1 s / the rate), and the
    // time of the last cue taken.
    std::int64_t credit_us_;
    std::int64_t last_cue_us_ = 0;
};

}  // namespace vibscore::daemon
