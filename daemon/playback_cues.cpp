#include "daemon/playback_cues.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "score/limits.hpp"

namespace vibscore::daemon {

namespace {

constexpr std::int64_t kSecond_us = 1'000'000;
constexpr std::int64_t kCueCost_us = kSecond_us / limits::max_playback_cues_per_second;
static_assert(kCueCost_us * limits::max_playback_cues_per_second == kSecond_us,
              "the bucket counts whole microseconds");

}  // namespace

PlaybackCues::PlaybackCues(std::shared_ptr<const render::CueSource> source, double duration_s,
                           int repeat, const render::CueAdaptation& adaptation)
    : source_(std::move(source)),
      duration_s_(duration_s),
      repeat_(repeat),
      adaptation_(adaptation),
      carry_(std::make_shared<render::PlannerCarry>()),
      credit_us_(kSecond_us) {}

bool PlaybackCues::within_rate(std::int64_t at_us) {
    credit_us_ = std::min(kSecond_us, credit_us_ + std::max<std::int64_t>(at_us - last_cue_us_, 0));
    last_cue_us_ = at_us;
    if (credit_us_ < kCueCost_us) {
        return false;
    }
    credit_us_ -= kCueCost_us;
    return true;
}

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
            const double at_s = static_cast<double>(pass_) * duration_s_ + cue->at;
            if (!within_rate(std::llround(at_s * 1e6))) {
                end_reason_ = "limit-exceeded: the score asks for more than " +
                              std::to_string(limits::max_playback_cues_per_second) +
                              " actuator commands and positions a second (at " +
                              std::to_string(std::llround(at_s * 1000.0)) + " ms)";
                ended_ = true;
                pass_stream_.reset();
                return false;
            }
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
