// vibscored with driver = evdev in the guest, against uinput force-feedback devices: what the
// daemon makes of a score at the real evdev interface (effects, plays and stops, their times,
// the gain, the erases), discovery by the udev vibra mark, and a device unplugged mid-playback.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <set>
#include <sstream>
#include <thread>

#include "tests/hil/score_expectations.hpp"
#include "tests/hil/uinput_vibrator.hpp"
#include "tests/hil/watched_playback.hpp"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {
namespace {

using namespace std::chrono_literals;
using testing::DaemonFixture;
using Kind = FfEvent::Kind;

const std::string kPhoneClef = "lra-phone.clef.xml";  // quarter = 0.2 s; strings 155..235 Hz

std::string listing(const std::vector<FfEvent>& timeline) {
    std::ostringstream out;
    for (const auto& event : timeline) {
        out << "\n  " << event;
    }
    return out.str();
}

bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

// A start or stop the player's drives should cause on the device, at `at` seconds.
struct ExpectedPlay {
    double at = 0.0;
    bool start = false;
    render::Cue drive;  // for a start: what it plays
};

// The backend's rule (docs/drivers/evdev.md): a drive that plays nothing stops the playing
// effect; any other drive stops the playing effect and starts its own, in one write.
std::vector<ExpectedPlay> expected_plays(const std::vector<render::Cue>& drives, bool periodic) {
    std::vector<ExpectedPlay> plays;
    bool playing = false;
    for (const auto& drive : drives) {
        const bool rises_from_silence = periodic && drive.ramp_s > 0.0 && drive.ramp_to > 0.0;
        if (playing) {
            plays.push_back({drive.at, false, drive});
            playing = false;
        }
        if (drive.amplitude > 0.0 || rises_from_silence) {
            plays.push_back({drive.at, true, drive});
            playing = true;
        }
    }
    return plays;
}

// The timeline once the device has read the daemon's last stop: the daemon writes it before it
// reports the playback finished, but the device's service thread may read it a moment after the
// report arrives here (seen on a loaded host: the final stop of 318 plays missing).
std::vector<FfEvent> timeline_after_the_last_stop(const UinputVibrator& vibrator) {
    vibscore::testing::wait_until([&] { return vibrator.playing().empty(); },
                                  std::chrono::seconds(5), std::chrono::milliseconds(2));
    return vibrator.timeline();
}

// A play or stop the device saw, with the effect its id held at that moment.
struct SeenPlay {
    FfEvent event;
    ff_effect effect{};
};

std::vector<SeenPlay> seen_plays(const std::vector<FfEvent>& timeline) {
    std::map<int, ff_effect> uploaded;
    std::vector<SeenPlay> plays;
    for (const auto& event : timeline) {
        if (event.kind == Kind::Upload && event.value == 0) {
            uploaded[event.effect_id] = event.effect;
        } else if (event.kind == Kind::Play) {
            plays.push_back({event, uploaded[event.effect_id]});
        }
    }
    return plays;
}

using EffectCheck = std::function<void(const ff_effect&, const render::Cue&)>;

// The device saw exactly the expected starts and stops, in order, each start with the effect
// its drive asks for and each stop of the effect that played, at the score's times relative
// to the first.
void expect_plays_follow_the_score(const std::vector<FfEvent>& timeline,
                                   const std::vector<ExpectedPlay>& expected,
                                   const EffectCheck& check_effect, double tolerance_s) {
    const auto seen = seen_plays(timeline);
    ASSERT_EQ(seen.size(), expected.size()) << listing(timeline);
    ASSERT_FALSE(seen.empty());
    int playing = -1;
    for (std::size_t i = 0; i < seen.size(); ++i) {
        SCOPED_TRACE("play event " + std::to_string(i) + " (score time " +
                     std::to_string(expected[i].at) + " s)");
        const auto& event = seen[i].event;
        ASSERT_EQ(event.value != 0, expected[i].start) << listing(timeline);
        if (expected[i].start) {
            EXPECT_EQ(event.value, 1);
            check_effect(seen[i].effect, expected[i].drive);
            playing = event.effect_id;
        } else {
            EXPECT_EQ(event.effect_id, playing) << "a stop of another effect than the playing one";
        }
        EXPECT_NEAR(seconds_between(seen[0].event.time, event.time),
                    expected[i].at - expected[0].at, tolerance_s)
            << listing(timeline);
    }
}

// docs/drivers/evdev.md: sine, period from the frequency in whole ms, magnitude from the
// strength, a ramp as an attack envelope, and no length (plays until stopped).
void expect_periodic_effect(const ff_effect& effect, const render::Cue& drive) {
    EXPECT_EQ(effect.type, FF_PERIODIC);
    EXPECT_EQ(effect.replay.length, 0);
    EXPECT_EQ(effect.replay.delay, 0);
    const auto& periodic = effect.u.periodic;
    EXPECT_EQ(periodic.waveform, FF_SINE);
    EXPECT_EQ(periodic.period, std::lround(1000.0 / drive.frequency_hz));
    EXPECT_EQ(periodic.offset, 0);
    EXPECT_EQ(periodic.envelope.fade_length, 0);
    if (drive.ramp_s > 0.0) {
        EXPECT_EQ(periodic.magnitude, std::lround(drive.ramp_to * 0x7fff));
        EXPECT_EQ(periodic.envelope.attack_length, std::lround(drive.ramp_s * 1000.0));
        EXPECT_EQ(periodic.envelope.attack_level, std::lround(drive.amplitude * 0x7fff));
    } else {
        EXPECT_EQ(periodic.magnitude, std::lround(drive.amplitude * 0x7fff));
        EXPECT_EQ(periodic.envelope.attack_length, 0);
    }
}

void expect_strong_rumble(const ff_effect& effect, const render::Cue& drive) {
    EXPECT_EQ(effect.type, FF_RUMBLE);
    EXPECT_EQ(effect.replay.length, 0);
    EXPECT_EQ(effect.u.rumble.strong_magnitude, std::lround(drive.amplitude * 0xffff));
    EXPECT_EQ(effect.u.rumble.weak_magnitude, 0);
}

std::set<int> ids_of(const std::vector<FfEvent>& timeline, Kind kind) {
    std::set<int> ids;
    for (const auto& event : timeline) {
        if (event.kind == kind) {
            ids.insert(event.effect_id);
        }
    }
    return ids;
}

std::size_t starts_in(const std::vector<FfEvent>& timeline) {
    return static_cast<std::size_t>(std::count_if(timeline.begin(), timeline.end(), [](auto& e) {
        return e.kind == Kind::Play && e.value != 0;
    }));
}

int event_number(const std::filesystem::path& node) {
    return std::stoi(node.filename().string().substr(std::string("event").size()));
}

TEST(DaemonEvdev, AScorePlaysAsPeriodicEffectsAtItsTimesWithTheGainFromIntensity) {
    UinputVibrator vibrator;  // periodic sine and rumble, gain, 16 effects
    DaemonFixture daemon(driver_config("evdev", "device = " + vibrator.event_node().string()));
    auto client = daemon.client();
    const auto capabilities = client->Capabilities();
    for (const char* name :
         {"amplitude-control", "frequency-control", "effect-memory", "envelopes", "gain-control"}) {
        EXPECT_TRUE(has(capabilities, name)) << name;
    }

    // Intensity goes to the device's gain, not into the effects.
    client->SetIntensity(0.8);
    const int gain = static_cast<int>(std::lround(0.8 * 0xffff));
    ASSERT_TRUE(vibrator.wait_for([&](auto& e) { return e.kind == Kind::Gain && e.value == gain; }))
        << listing(vibrator.timeline());

    // 235 Hz at full strength; a crescendo from silence to 0.6 at 170 Hz, directly followed by
    // 0.2 at 200 Hz.
    const auto score = one_bar_score(kPhoneClef,
                                     "<Note length=\"quarter\" number=\"9\" string=\"6\"/>"
                                     "<Rest length=\"8th\"/>"
                                     "<Note length=\"half\" number=\"5\" string=\"2\" "
                                     "dynamics=\"crescendo\"/>"
                                     "<Note length=\"quarter\" number=\"1\" string=\"4\"/>");
    render::CueAdaptation adaptation;
    adaptation.envelopes = true;
    const auto expected = expected_plays(expected_drives(score, adaptation), true);

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const auto timeline = timeline_after_the_last_stop(vibrator);
    expect_plays_follow_the_score(timeline, expected, expect_periodic_effect,
                                  played.onset_tolerance_s);

    // The numbers themselves, for the record: 235 Hz is a 4 ms period, full strength 0x7fff
    // (not scaled by the intensity), the crescendo an attack envelope rising over ~0.36 s.
    const auto seen = seen_plays(timeline);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen[0].effect.u.periodic.period, 4);
    EXPECT_EQ(seen[0].effect.u.periodic.magnitude, 0x7fff);
    const auto crescendo = std::find_if(seen.begin(), seen.end(), [](const SeenPlay& play) {
        return play.event.value != 0 && play.effect.u.periodic.envelope.attack_length > 0;
    });
    ASSERT_NE(crescendo, seen.end()) << listing(timeline);
    EXPECT_EQ(crescendo->effect.u.periodic.period, 6);
    EXPECT_LT(crescendo->effect.u.periodic.envelope.attack_level, 0x7fff / 20);
    EXPECT_NEAR(crescendo->effect.u.periodic.magnitude, 0.6 * 0x7fff, 0.02 * 0x7fff);
    EXPECT_NEAR(crescendo->effect.u.periodic.envelope.attack_length, 360, 10);
    // The gain was in place before anything played.
    const auto first_play = std::find_if(timeline.begin(), timeline.end(),
                                         [](const FfEvent& e) { return e.kind == Kind::Play; });
    const auto last_gain = std::find_if(std::make_reverse_iterator(first_play), timeline.rend(),
                                        [](const FfEvent& e) { return e.kind == Kind::Gain; });
    ASSERT_NE(last_gain, timeline.rend()) << listing(timeline);
    EXPECT_EQ(last_gain->value, gain);

    // Every effect the daemon uploaded is erased when it stops, and nothing plays.
    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    const auto after = vibrator.timeline();
    const auto uploaded = ids_of(after, Kind::Upload);
    EXPECT_LE(uploaded.size(), 2u) << "the backend keeps two effect slots" << listing(after);
    EXPECT_EQ(ids_of(after, Kind::Erase), uploaded) << listing(after);
    EXPECT_TRUE(vibrator.effects().empty()) << listing(after);
    EXPECT_TRUE(vibrator.playing().empty()) << listing(after);
}

TEST(DaemonEvdev, ARumbleOnlyDeviceFollowsACrescendoInSmallSteps) {
    UinputVibratorOptions options;
    options.ff_bits = {FF_RUMBLE, FF_GAIN};
    UinputVibrator vibrator(options);
    DaemonFixture daemon(driver_config("evdev", "device = " + vibrator.event_node().string()));
    auto client = daemon.client();
    const auto capabilities = client->Capabilities();
    EXPECT_TRUE(has(capabilities, "amplitude-control"));
    EXPECT_FALSE(has(capabilities, "envelopes"));
    EXPECT_FALSE(has(capabilities, "frequency-control"));

    const auto score = one_bar_score(
        kPhoneClef, "<Note length=\"whole\" number=\"9\" string=\"3\" dynamics=\"crescendo\"/>");
    render::CueAdaptation adaptation;
    adaptation.frequency = false;
    const auto expected = expected_plays(expected_drives(score, adaptation), false);

    const auto played = play_to_the_end(daemon, score);
    ASSERT_TRUE(played.completed);
    const auto timeline = timeline_after_the_last_stop(vibrator);
    // Hundreds of events: after a stall of the emulated guest the player catches up over a few
    // steps, each late by a little more than the stall.
    expect_plays_follow_the_score(timeline, expected, expect_strong_rumble,
                                  kOnsetTolerance_s + played.onset_tolerance_s);

    // Along the 0.8 s crescendo the magnitude rises step by step, at least 100 times a second.
    const auto seen = seen_plays(timeline);
    std::vector<SeenPlay> starts;
    std::copy_if(seen.begin(), seen.end(), std::back_inserter(starts),
                 [](const SeenPlay& play) { return play.event.value != 0; });
    ASSERT_GE(starts.size(), 80u) << listing(timeline);
    for (std::size_t i = 1; i < starts.size(); ++i) {
        EXPECT_GT(starts[i].effect.u.rumble.strong_magnitude,
                  starts[i - 1].effect.u.rumble.strong_magnitude)
            << "step " << i;
    }
    const double span_s = seconds_between(starts.front().event.time, starts.back().event.time);
    EXPECT_GE(static_cast<double>(starts.size() - 1) / span_s, 100.0)
        << starts.size() << " updates in " << span_s << " s";
    EXPECT_GT(starts.back().effect.u.rumble.strong_magnitude, 0.95 * 0xffff);

    EXPECT_EQ(daemon.stop_daemon(), 0) << daemon.daemon_log();
    EXPECT_TRUE(vibrator.effects().empty()) << listing(vibrator.timeline());
}

TEST(DaemonEvdev, WithoutADeviceSettingDiscoveryTakesTheOneUdevMarksAsTheVibra) {
    UinputVibrator gamepad;  // force feedback too, and the lower event number, but no mark
    UinputVibrator vibra(UinputVibratorOptions::phone_vibrator());
    ASSERT_LT(event_number(gamepad.event_node()), event_number(vibra.event_node()))
        << "the unmarked device must come first for this test to show the mark decides";
    DaemonFixture daemon(driver_config("evdev", ""));
    EXPECT_NE(daemon.daemon_log().find("discovered " + vibra.event_node().string() +
                                       " (udev: FEEDBACKD_TYPE=vibra)"),
              std::string::npos)
        << daemon.daemon_log();

    auto client = daemon.client();
    const auto id = client->Play("touch-tick", {});
    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed");
    EXPECT_EQ(starts_in(vibra.timeline()), 1u) << listing(vibra.timeline());
    EXPECT_EQ(gamepad.timeline().size(), 1u) << "only its creation" << listing(gamepad.timeline());
}

TEST(DaemonEvdev, AnUnpluggedDeviceEndsThePlaybackAndTheNextPlayFindsItAgain) {
    UinputVibrator vibra(UinputVibratorOptions::phone_vibrator());
    // Discovery, so the daemon looks for the device wherever it comes back.
    DaemonFixture daemon(driver_config("evdev", ""));
    auto client = daemon.client();
    std::string notes;
    for (int i = 0; i < 4; ++i) {
        notes += "<Note length=\"quarter\" number=\"7\" string=\"4\"/><Rest length=\"8th\"/>";
    }
    const auto id = client->Play(one_bar_score(kPhoneClef, notes), {});
    ASSERT_TRUE(eventually([&] { return starts_in(vibra.timeline()) >= 2; }))
        << listing(vibra.timeline());
    vibra.destroy();

    std::string reason;
    ASSERT_TRUE(client->wait_finished(id, &reason, 5s)) << daemon.daemon_log();
    EXPECT_EQ(reason.rfind("device-error: ", 0), 0u) << reason;
    EXPECT_NE(reason.find("evdev"), std::string::npos) << reason;
    EXPECT_FALSE(client->List("scores").empty()) << "the daemon serves on";

    vibra.recreate();
    const auto again = client->Play("touch-tick", {});
    ASSERT_TRUE(client->wait_finished(again, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed") << daemon.daemon_log();
    const auto timeline = vibra.timeline();
    const auto created = std::find_if(timeline.rbegin(), timeline.rend(),
                                      [](const FfEvent& e) { return e.kind == Kind::Created; });
    const std::vector<FfEvent> since_recreated(created.base(), timeline.end());
    EXPECT_EQ(starts_in(since_recreated), 1u) << listing(timeline);
}

TEST(DaemonEvdev, ADeviceRepluggedWhileIdlePlaysTheNextScoreAtOnce) {
    UinputVibrator vibra(UinputVibratorOptions::phone_vibrator());
    DaemonFixture daemon(driver_config("evdev", ""));
    auto client = daemon.client();
    std::string reason;
    auto id = client->Play("touch-tick", {});
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed");
    // Unplugged and back while the daemon had nothing to play: the node it holds is dead, and
    // nothing told it. The first Play after that plays all the same.
    vibra.recreate();
    vibra.clear_timeline();
    id = client->Play("touch-tick", {});
    ASSERT_TRUE(client->wait_finished(id, &reason)) << daemon.daemon_log();
    EXPECT_EQ(reason, "completed") << daemon.daemon_log();
    EXPECT_EQ(starts_in(vibra.timeline()), 1u) << listing(vibra.timeline());
}

}  // namespace
}  // namespace vibscore::hil
