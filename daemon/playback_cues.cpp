#include "daemon/playback_cues.hpp"

#include <utility>

namespace vibscore::daemon {

PlaybackCues::PlaybackCues(std::shared_ptr<const render::CueSource> source, double duration_s,
                           int repeat, const render::CueAdaptation& adaptation)
    : source_(std::move(source)),
      duration_s_(duration_s),
      repeat_(repeat),
      adaptation_(adaptation),
      carry_(std::make_shared<render::PlannerCarry>()) {}

bool PlaybackCues::read() {
    while (!ended_) {
        if (!pass_stream_) {
            const bool last = repeat_ >= 0 && pass_ >= static_cast<std::uint64_t>(repeat_);
            pass_stream_ = std::make_unique<render::AdaptedCueStream>(
                source_->pass(), duration_s_, adaptation_, render::PassLink{carry_, last});
            pass_had_cues_ = false;
        }
        if (auto cue = pass_stream_->next()) {
            pass_had_cues_ = true;
            read_ahead_.push_back({*cue, pass_});
            return true;
        }
        pass_stream_.reset();
        // A pass without cues would repeat without end and without time passing.
        const bool another =
            pass_had_cues_ && (repeat_ < 0 || pass_ < static_cast<std::uint64_t>(repeat_));
        if (!another) {
            ended_ = true;
            break;
        }
        ++pass_;
    }
    return false;
}

const PassCue* PlaybackCues::ahead(std::size_t index) {
    while (read_ahead_.size() <= index) {
        if (!read()) {
            return nullptr;
        }
    }
    return &read_ahead_[index];
}

void PlaybackCues::pop() {
    if (!read_ahead_.empty()) {
        read_ahead_.pop_front();
    }
}

}  // namespace vibscore::daemon
