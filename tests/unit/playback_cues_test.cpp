// The cues one playback runs: its passes in order, and the bound on how many a second it may
// ask for (limits::max_playback_cues_per_second), tested at the last cue allowed and the first
// refused, in bursts and sustained.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "daemon/play_request.hpp"
#include "daemon/playback_cues.hpp"
#include "score/limits.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::HasSubstr;

constexpr auto kRate = static_cast<std::size_t>(limits::max_playback_cues_per_second);

render::Cue position_at(double at) {
    render::Cue cue;
    cue.at = at;
    cue.kind = render::Cue::Kind::position;
    return cue;
}

// `burst` cues at 0, then one every `spacing_s` from `spacing_s` on, `sustained` of them.
std::vector<render::Cue> burst_then_every(std::size_t burst, std::size_t sustained,
                                          double spacing_s) {
    std::vector<render::Cue> cues(burst, position_at(0.0));
    for (std::size_t i = 1; i <= sustained; ++i) {
        cues.push_back(position_at(static_cast<double>(i) * spacing_s));
    }
    return cues;
}

struct Ran {
    std::size_t cues = 0;
    std::string reason;
};

Ran run(std::vector<render::Cue> cues, double duration_s, int repeat = 0) {
    PlaybackCues playback(std::make_shared<render::CueList>(std::move(cues)), duration_s, repeat,
                          render::CueAdaptation{});
    Ran ran;
    while (playback.ahead(0) != nullptr) {
        playback.pop();
        ++ran.cues;
    }
    ran.reason = playback.end_reason();
    return ran;
}

TEST(PlaybackCues, ABurstOfOneSecondsWorthOfCuesAtOneInstantPlays) {
    const auto ran = run(burst_then_every(kRate, 0, 0.0), 1.0);
    EXPECT_EQ(ran.cues, kRate);
    EXPECT_EQ(ran.reason, "completed");
}

TEST(PlaybackCues, OneCueMoreThanTheBurstEndsThePlaybackBeforeIt) {
    const auto ran = run(burst_then_every(kRate + 1, 0, 0.0), 1.0);
    EXPECT_EQ(ran.cues, kRate);
    EXPECT_EQ(ran.reason,
              "limit-exceeded: the score asks for more than 1000 actuator commands and positions "
              "a second (at 0 ms)");
}

TEST(PlaybackCues, AfterTheBurstCuesAtTheRateItselfPlayOn) {
    // Every cue after the burst comes exactly 1 s / rate after the one before: the last allowed.
    const auto ran = run(burst_then_every(kRate, 2 * kRate, 1.0 / kRate), 3.0);
    EXPECT_EQ(ran.cues, 3 * kRate);
    EXPECT_EQ(ran.reason, "completed");
}

TEST(PlaybackCues, AfterTheBurstACueAMicrosecondTooSoonEndsThePlayback) {
    auto cues = burst_then_every(kRate, 100, 1.0 / kRate);
    cues.push_back(position_at(0.100 + 1.0 / kRate - 1e-6));  // the first refused
    cues.push_back(position_at(0.5));
    const auto ran = run(cues, 1.0);
    EXPECT_EQ(ran.cues, kRate + 100);
    EXPECT_THAT(ran.reason, HasSubstr("(at 101 ms)"));
}

TEST(PlaybackCues, ASecondOfQuietRefillsTheBurstAndRepeatsAreCountedInScheduleTime) {
    // Each pass: a full burst at its start, then nothing for the rest of its second.
    const auto ran = run(burst_then_every(kRate, 0, 0.0), 1.0, 4);
    EXPECT_EQ(ran.cues, 5 * kRate);
    EXPECT_EQ(ran.reason, "completed");
    // The same passes half a second apart refill only half the burst.
    const auto crowded = run(burst_then_every(kRate, 0, 0.0), 0.5, 4);
    EXPECT_EQ(crowded.cues, kRate + kRate / 2);
    EXPECT_THAT(crowded.reason, HasSubstr("(at 500 ms)"));
}

// The bound must never touch a real score: every shipped one plays whole, on an actuator that
// takes strength as given and on one that pulse-modulates it.
TEST(PlaybackCues, EveryShippedScorePlaysWithinTheBoundOnEveryKindOfActuator) {
    const std::filesystem::path shipped = vibscore::testing::required_env("VIBSCORE_CLEFS");
    vibscore::testing::TempDir store;
    const Registry registry(shipped, store.path());
    const auto scores = registry.list(DocumentKind::score);
    ASSERT_GT(scores.size(), 20u);
    for (const auto& entry : scores) {
        const auto request =
            make_playback_request(find_score_to_play(registry, entry.name, {}, {}), {}, 0.030);
        for (const bool amplitude : {true, false}) {
            render::CueAdaptation adaptation;
            adaptation.amplitude = amplitude;
            // Three passes: a repeat comes right after the pass before.
            PlaybackCues cues(request.cues, request.duration_s, 2, adaptation);
            while (cues.ahead(0) != nullptr) {
                cues.pop();
            }
            EXPECT_EQ(cues.end_reason(), "completed") << entry.name << " amplitude " << amplitude;
        }
    }
}

}  // namespace
}  // namespace vibscore::daemon
