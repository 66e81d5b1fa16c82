// What a playback holds in memory, against the length of its score: the request Play hands the
// player, and the player's cues as it plays them. Every operator new of this program is
// counted, so the test sees what the code under it allocates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <new>

#include "daemon/play_request.hpp"
#include "daemon/playback_cues.hpp"
#include "tests/support/support.hpp"

namespace {

std::size_t g_live_bytes = 0;
std::size_t g_peak_bytes = 0;

// Each block carries its size in front of it, so delete knows what it gives back.
constexpr std::size_t kHeader = alignof(std::max_align_t);

void* counted_new(std::size_t size) {
    auto* block = static_cast<unsigned char*>(std::malloc(size + kHeader));
    if (block == nullptr) {
        throw std::bad_alloc();
    }
    *reinterpret_cast<std::size_t*>(block) = size;
    g_live_bytes += size;
    g_peak_bytes = std::max(g_peak_bytes, g_live_bytes);
    return block + kHeader;
}

void counted_delete(void* pointer) noexcept {
    if (pointer == nullptr) {
        return;
    }
    auto* block = static_cast<unsigned char*>(pointer) - kHeader;
    g_live_bytes -= *reinterpret_cast<std::size_t*>(block);
    std::free(block);
}

}  // namespace

void* operator new(std::size_t size) {
    return counted_new(size);
}
void* operator new[](std::size_t size) {
    return counted_new(size);
}
void operator delete(void* pointer) noexcept {
    counted_delete(pointer);
}
void operator delete[](void* pointer) noexcept {
    counted_delete(pointer);
}
void operator delete(void* pointer, std::size_t) noexcept {
    counted_delete(pointer);
}
void operator delete[](void* pointer, std::size_t) noexcept {
    counted_delete(pointer);
}

namespace vibscore::daemon {
namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;

// `notes` whole notes of 4 s, each a crescendo to the next strength: the cue schedule follows
// every one in 5 ms steps, 800 actuator commands per note.
ScoreToPlay crescendos(int notes) {
    std::string bars;
    for (int i = 0; i < notes; ++i) {
        bars += "<Bar clef=\"c\"><Note length=\"whole\" number=\"" + std::to_string(1 + i % 9) +
                "\" string=\"1\" dynamics=\"crescendo\"/></Bar>";
    }
    return {vibscore::testing::bundle_from(
                vibscore::testing::one_clef_score(bars),
                {{"c.xml", vibscore::testing::sine_clef(
                               1.0, {170}, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9})}}),
            "crescendos"};
}

// Bytes a request made for `score` keeps allocated while it waits to be played.
std::size_t request_bytes(const ScoreToPlay& score) {
    const std::size_t before = g_live_bytes;
    const PlaybackRequest request = make_playback_request(score, {}, 0.030);
    return g_live_bytes - before;
}

TEST(PlaybackMemory, TheRequestForAnHourOfCrescendosHoldsNoMoreThanAMegabyteMoreThanAMinutes) {
    const auto minute = crescendos(15);
    const auto hour = crescendos(900);
    const std::size_t minute_bytes = request_bytes(minute);
    const std::size_t hour_bytes = request_bytes(hour);
    // 720,000 drives of an hour would take 46 MB as a list.
    EXPECT_LT(hour_bytes, minute_bytes + kMiB)
        << "minute " << minute_bytes << ", hour " << hour_bytes;
}

TEST(PlaybackMemory, PlayingAnHourOfCrescendosThroughReadsNoMoreThanItsReadAhead) {
    const PlaybackRequest request = make_playback_request(crescendos(900), {}, 0.030);
    PlaybackCues cues(request.cues, request.duration_s, 0, render::CueAdaptation{});
    const std::size_t before = g_live_bytes;
    g_peak_bytes = before;
    std::size_t played = 0;
    double last_at = 0.0;
    // The player reads up to 4096 cues ahead of the one it plays.
    while (const PassCue* next = cues.ahead(0)) {
        ASSERT_GE(next->cue.at, last_at);
        last_at = next->cue.at;
        cues.ahead(4095);
        cues.pop();
        ++played;
    }
    EXPECT_GT(played, 700'000u);
    EXPECT_NEAR(last_at, 3600.0, 1e-6);
    EXPECT_LT(g_peak_bytes - before, kMiB) << "peak while playing";
}

}  // namespace
}  // namespace vibscore::daemon
