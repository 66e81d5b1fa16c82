// The virtual vibra's pure parts: force-feedback effects as patterns (the kernel's ff-memless
// rules), its [virtual-vibra] settings, and its effects played through a real Player. The
// uinput device itself is in the hil tier (tests/hil/virtual_vibra_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>

#include "daemon/player.hpp"
#include "daemon/virtual_vibra/ff_effect_pattern.hpp"
#include "daemon/virtual_vibra/ff_effect_player.hpp"
#include "daemon/virtual_vibra/virtual_vibra.hpp"

namespace vibscore::daemon {
namespace {

ff_effect rumble(std::uint16_t strong, std::uint16_t weak, std::uint16_t length_ms,
                 std::uint16_t delay_ms = 0) {
    ff_effect effect{};
    effect.type = FF_RUMBLE;
    effect.id = -1;
    effect.u.rumble.strong_magnitude = strong;
    effect.u.rumble.weak_magnitude = weak;
    effect.replay.length = length_ms;
    effect.replay.delay = delay_ms;
    return effect;
}

ff_effect periodic(std::uint16_t waveform, std::uint16_t period_ms, std::int16_t magnitude,
                   std::uint16_t length_ms) {
    ff_effect effect{};
    effect.type = FF_PERIODIC;
    effect.id = -1;
    effect.u.periodic.waveform = waveform;
    effect.u.periodic.period = period_ms;
    effect.u.periodic.magnitude = magnitude;
    effect.replay.length = length_ms;
    return effect;
}

ff_effect constant(std::int16_t level, std::uint16_t length_ms, ff_envelope envelope) {
    ff_effect effect{};
    effect.type = FF_CONSTANT;
    effect.id = -1;
    effect.u.constant.level = level;
    effect.u.constant.envelope = envelope;
    effect.replay.length = length_ms;
    return effect;
}

TEST(FfEffectPattern, RumbleHoldsTheStrongerMotorForItsLengthAfterItsDelay) {
    EXPECT_EQ(ff_effect_pattern(rumble(0x8000, 0xffff, 150, 20)),
              (VibrationPattern{{0.02, 0, 0, 0}, {0.15, 1, 1, 0}}));
    const auto half = ff_effect_pattern(rumble(0, 0x8000, 100));
    ASSERT_EQ(half.size(), 1u);
    EXPECT_NEAR(half[0].from, 0.5, 1e-4);
    EXPECT_EQ(half[0].frequency_hz, 0.0) << "a rumble motor has its own frequency";
}

TEST(FfEffectPattern, PeriodicPlaysItsPeriodAsAFrequencyInsideTheBandOnly) {
    for (const auto waveform : {FF_SINE, FF_SQUARE, FF_TRIANGLE}) {
        EXPECT_EQ(ff_effect_pattern(periodic(waveform, 5, 0x7fff, 300)),
                  (VibrationPattern{{0.3, 1, 1, 200}}))
            << waveform;
    }
    EXPECT_EQ(ff_effect_pattern(periodic(FF_SINE, 100, 0x7fff, 300))[0].frequency_hz, 0.0)
        << "10 Hz is below the band: the actuator's own frequency";
    EXPECT_EQ(ff_effect_pattern(periodic(FF_SINE, 0, 0x7fff, 300))[0].frequency_hz, 0.0);
    EXPECT_NEAR(ff_effect_pattern(periodic(FF_SINE, 5, -0x4000, 300))[0].from, 0.5, 1e-4)
        << "a negative magnitude drives as hard as a positive one";
}

TEST(FfEffectPattern, EnvelopeRampsFromTheAttackLevelAndToTheFadeLevel) {
    const auto pattern = ff_effect_pattern(constant(0x7fff, 400, {100, 0, 100, 0x4000}));
    ASSERT_EQ(pattern.size(), 3u);
    EXPECT_EQ(pattern[0], (PatternStep{0.1, 0, 1, 0}));
    EXPECT_DOUBLE_EQ(pattern[1].seconds, 0.2);
    EXPECT_EQ(pattern[1].from, 1.0);
    EXPECT_EQ(pattern[1].to, 1.0);
    EXPECT_DOUBLE_EQ(pattern[2].seconds, 0.1);
    EXPECT_EQ(pattern[2].from, 1.0);
    EXPECT_NEAR(pattern[2].to, 0.5, 1e-4);
}

TEST(FfEffectPattern, AnAttackLongerThanTheEffectIsCutWhereItHasGot) {
    const auto pattern = ff_effect_pattern(constant(0x7fff, 50, {200, 0, 0, 0}));
    ASSERT_EQ(pattern.size(), 1u);
    EXPECT_DOUBLE_EQ(pattern[0].seconds, 0.05);
    EXPECT_EQ(pattern[0].from, 0.0);
    EXPECT_NEAR(pattern[0].to, 0.25, 1e-9);
}

TEST(FfEffectPattern, OverlappingAttackAndFadeFadeFromWhereTheAttackLeftOff) {
    // 100 ms: attack over 80 ms from 0, fade over the last 60 ms to 0 (so from 40 ms on).
    const auto pattern = ff_effect_pattern(constant(0x7fff, 100, {80, 0, 60, 0}));
    ASSERT_EQ(pattern.size(), 2u);
    EXPECT_DOUBLE_EQ(pattern[0].seconds, 0.08);
    EXPECT_DOUBLE_EQ(pattern[1].seconds, 0.02);
    EXPECT_NEAR(pattern[1].from, 1.0 / 3.0, 1e-9) << "the fade is 40 of its 60 ms along";
    EXPECT_EQ(pattern[1].to, 0.0);
}

TEST(FfEffectPattern, LengthZeroWithoutLeadInLoopsOneSecondWithoutFading) {
    const auto effect = constant(0x7fff, 0, {0, 0, 100, 0});
    EXPECT_TRUE(ff_effect_loops(effect));
    EXPECT_EQ(ff_effect_pattern(effect), (VibrationPattern{{1.0, 1, 1, 0}}));
    EXPECT_TRUE(ff_effect_loops(rumble(0xffff, 0, 0)));
    EXPECT_FALSE(ff_effect_loops(rumble(0xffff, 0, 10)));
}

TEST(FfEffectPattern, LengthZeroAfterADelayOrAttackHoldsLongAfterIt) {
    const auto delayed = rumble(0xffff, 0, 0, 50);
    EXPECT_FALSE(ff_effect_loops(delayed));
    EXPECT_EQ(ff_effect_pattern(delayed),
              (VibrationPattern{{0.05, 0, 0, 0}, {kUntilStoppedSeconds, 1, 1, 0}}));
    const auto attacked = constant(0x7fff, 0, {50, 0, 100, 0});
    EXPECT_FALSE(ff_effect_loops(attacked));
    const auto pattern = ff_effect_pattern(attacked);
    ASSERT_EQ(pattern.size(), 2u);
    EXPECT_EQ(pattern[0], (PatternStep{0.05, 0, 1, 0}));
    EXPECT_DOUBLE_EQ(pattern_seconds(pattern), kUntilStoppedSeconds);
    EXPECT_EQ(pattern[1].to, 1.0) << "no fade: it never ends by itself";
}

TEST(FfEffectPattern, RefusesWhatAVibratorCannotPlay) {
    ff_effect spring{};
    spring.type = FF_SPRING;
    EXPECT_THROW(ff_effect_pattern(spring), std::invalid_argument);
    EXPECT_THROW(ff_effect_pattern(periodic(FF_CUSTOM, 5, 0x7fff, 100)), std::invalid_argument);
    EXPECT_THROW(ff_effect_pattern(periodic(FF_SAW_UP, 5, 0x7fff, 100)), std::invalid_argument);
}

TEST(FfEffectPattern, DescriptionsNameTypeWaveformLengthAndDelay) {
    EXPECT_EQ(describe_ff_effect(rumble(1, 1, 150, 20)), "rumble 150 ms after 20 ms");
    EXPECT_EQ(describe_ff_effect(periodic(FF_SQUARE, 10, 1, 0)),
              "periodic square 10 ms period until stopped");
}

TEST(VirtualVibraSettings, OffByDefaultWithNotificationUsage) {
    const auto settings = parse_virtual_vibra_settings({});
    EXPECT_FALSE(settings.enabled);
    EXPECT_EQ(settings.usage, Usage::notification);
    EXPECT_EQ(settings.effects_max, 16u);
}

TEST(VirtualVibraSettings, ReadsEveryKeyAndRejectsWrongOnes) {
    const auto settings = parse_virtual_vibra_settings(
        {{"enabled", "true"}, {"usage", "touch"}, {"name", "phone vibra"}, {"effects-max", "4"}});
    EXPECT_TRUE(settings.enabled);
    EXPECT_EQ(settings.usage, Usage::touch);
    EXPECT_EQ(settings.name, "phone vibra");
    EXPECT_EQ(settings.effects_max, 4u);
    EXPECT_THROW(parse_virtual_vibra_settings({{"usage", "loud"}}), std::invalid_argument);
    EXPECT_THROW(parse_virtual_vibra_settings({{"effects-max", "0"}}), std::invalid_argument);
    EXPECT_THROW(parse_virtual_vibra_settings({{"enable", "true"}}), std::invalid_argument);
}

class RecordingActuator : public drivers::Actuator {
  public:
    std::string_view driver_name() const override { return "recording"; }
    drivers::Capabilities capabilities() const override { return capabilities_; }
    void apply(const drivers::Drive& drive) override { applied.push_back(drive); }
    void off() noexcept override { applied.push_back({}); }
    std::vector<drivers::Drive> applied;
    drivers::Capabilities capabilities_{.frequency_control = true};
};

class Finishes : public PlayerListener {
  public:
    explicit Finishes(EventLoop& loop) : loop_(loop) {}
    void playback_started(std::uint64_t, const std::string& label) override {
        events.push_back("started " + label);
    }
    void playback_position(std::uint64_t, std::size_t, std::size_t) override {}
    void playback_finished(std::uint64_t, const std::string& reason) override {
        events.push_back("finished " + reason);
        loop_.exit(0);
    }
    std::vector<std::string> events;

  private:
    EventLoop& loop_;
};

class FfEffectPlayerTest : public ::testing::Test {
  protected:
    static void effect_id(FfEffectPlayer& into, ff_effect effect, int id) {
        effect.id = static_cast<std::int16_t>(id);
        ASSERT_EQ(into.upload(effect), 0);
    }
    int upload(ff_effect effect, int id) {
        effect.id = static_cast<std::int16_t>(id);
        return effects.upload(effect);
    }
    bool drove(double amplitude, double frequency_hz) const {
        for (const auto& drive : actuator.applied) {
            if (std::abs(drive.amplitude - amplitude) < 1e-3 &&
                drive.frequency_hz == frequency_hz) {
                return true;
            }
        }
        return false;
    }

    EventLoop loop;
    RecordingActuator actuator;
    Finishes listener{loop};
    Player player{loop, actuator, listener};
    FfEffectPlayer effects{[this](const auto& work) { work(player); }, Usage::notification, 0.03};
};

TEST_F(FfEffectPlayerTest, APlayedEffectDrivesTheActuatorAndCompletes) {
    ASSERT_EQ(upload(periodic(FF_SINE, 5, 0x4000, 40), 0), 0);
    EXPECT_EQ(effects.effects(), 1u);
    actuator.applied.clear();
    effects.play(0, 1);
    loop.run();
    EXPECT_TRUE(drove(0.5, 200)) << actuator.applied.size() << " drives";
    EXPECT_EQ(actuator.applied.back().amplitude, 0.0);
    ASSERT_EQ(listener.events.size(), 2u);
    EXPECT_EQ(listener.events[0], "started virtual-vibra 0: periodic sine 5 ms period 40 ms");
    EXPECT_EQ(listener.events[1], "finished completed");
}

TEST_F(FfEffectPlayerTest, TheRepeatCountPlaysTheEffectThatManyTimes) {
    ASSERT_EQ(upload(rumble(0xffff, 0, 10, 10), 0), 0);
    actuator.applied.clear();
    effects.play(0, 3);
    loop.run();
    const auto starts = std::count_if(actuator.applied.begin(), actuator.applied.end(),
                                      [](const drivers::Drive& d) { return d.amplitude == 1.0; });
    EXPECT_EQ(starts, 3) << "each pass: delay off, then full";
}

TEST_F(FfEffectPlayerTest, AnEffectUntilStoppedPlaysOnAndOnWhateverTheCount) {
    ASSERT_EQ(upload(rumble(0xffff, 0, 0), 0), 0);
    effects.play(0, 1);
    const auto id = player.current_id();
    ASSERT_TRUE(id);
    EventLoop::Timer later(loop, [this] { loop.exit(0); });
    later.arm(monotonic_now_us() + 1'100'000);
    loop.run();
    EXPECT_EQ(player.current_id(), id) << "past its one-second pass";
    effects.play(0, 0);
    EXPECT_FALSE(player.current_id());
}

// No one holds the vibrator through it either: an effect looping until stopped (a game that never
// sends stop) ends at its usage's maximum on-time, asked at the play, as a Play's would.
TEST_F(FfEffectPlayerTest, AnEffectUntilStoppedEndsAtTheMaximumOnTime) {
    std::optional<double> limit = 0.2;
    FfEffectPlayer limited{[this](const auto& work) { work(player); }, Usage::notification, 0.03,
                           [&limit] { return limit; }};
    effect_id(limited, rumble(0xffff, 0, 0), 0);
    const auto started_us = monotonic_now_us();
    limited.play(0, 1);
    ASSERT_TRUE(player.current_id());
    loop.run();  // returns once nothing plays
    EXPECT_GE(monotonic_now_us() - started_us, 200'000u);
    ASSERT_FALSE(listener.events.empty());
    EXPECT_EQ(listener.events.back().rfind("finished limit-exceeded: played for its maximum", 0),
              0u)
        << listener.events.back();
}

TEST_F(FfEffectPlayerTest, PlayZeroAndEraseStopWhatPlays) {
    ASSERT_EQ(upload(rumble(0xffff, 0, 0), 3), 0);
    ASSERT_EQ(upload(rumble(0x8000, 0, 0), 4), 0);
    effects.play(3, 1);
    ASSERT_TRUE(player.current_id());
    effects.play(4, 0);  // another effect's stop leaves this one playing
    EXPECT_TRUE(player.current_id());
    effects.play(3, 0);
    EXPECT_FALSE(player.current_id());
    effects.play(4, 1);
    ASSERT_TRUE(player.current_id());
    effects.erase(4);
    EXPECT_FALSE(player.current_id()) << "a client closing its fd erases its effects";
    EXPECT_EQ(effects.effects(), 1u);
}

TEST_F(FfEffectPlayerTest, PlayingOneEffectEndsTheOtherAsOneVibraDoes) {
    ASSERT_EQ(upload(rumble(0xffff, 0, 0), 0), 0);
    ASSERT_EQ(upload(rumble(0x8000, 0, 0), 1), 0);
    effects.play(0, 1);
    effects.play(1, 1);
    EXPECT_EQ(listener.events.at(1), "finished stopped");
    EXPECT_TRUE(drove(0.5, 0));
    effects.play(0, 0);
    EXPECT_TRUE(player.current_id()) << "effect 0 no longer plays: its stop is no one's";
}

TEST_F(FfEffectPlayerTest, GainScalesEveryPlayFromThenOn) {
    effects.gain(0x8000);
    EXPECT_NEAR(effects.current_gain(), 0.5, 1e-4);
    ASSERT_EQ(upload(rumble(0xffff, 0, 0), 0), 0);
    effects.play(0, 1);
    EXPECT_TRUE(drove(0.5, 0));
    EXPECT_FALSE(drove(1.0, 0));
}

TEST_F(FfEffectPlayerTest, AMoreImportantPlaybackKeepsTheActuator) {
    PlaybackRequest alarm;
    alarm.label = "alarm";
    std::vector<render::Cue> cues(2);
    cues[0].amplitude = 0.2;
    cues[1].at = 10;  // off again at its end
    alarm.cues = std::make_shared<render::CueList>(std::move(cues));
    alarm.duration_s = 10;
    alarm.usage = Usage::alarm;
    const auto alarm_id = player.play(alarm);
    ASSERT_EQ(upload(rumble(0xffff, 0, 100), 0), 0);
    effects.play(0, 1);
    EXPECT_EQ(player.current_id(), alarm_id);
    effects.play(0, 0);
    EXPECT_EQ(player.current_id(), alarm_id) << "the vibra stops only its own playback";
}

TEST_F(FfEffectPlayerTest, UnplayableEffectsAreRefusedAsTheKernelExpects) {
    ff_effect spring{};
    spring.type = FF_SPRING;
    EXPECT_EQ(upload(spring, 0), -EINVAL);
    EXPECT_EQ(effects.effects(), 0u);
    effects.play(0, 1);  // the kernel would not pass it on; nothing to play either way
    EXPECT_FALSE(player.current_id());
}

TEST_F(FfEffectPlayerTest, AnOnOffActuatorPlaysAHalfStrengthEffectAsPulses) {
    actuator.capabilities_ = {.amplitude_control = false, .pulse_period_s = 0.02};
    ASSERT_EQ(upload(rumble(0x8000, 0, 100), 0), 0);
    actuator.applied.clear();
    effects.play(0, 1);
    loop.run();
    const auto on = std::count_if(actuator.applied.begin(), actuator.applied.end(),
                                  [](const drivers::Drive& d) { return d.amplitude == 1.0; });
    EXPECT_GE(on, 4) << "about one pulse per 20 ms period over 100 ms";
    EXPECT_FALSE(drove(0.5, 0)) << "no strength it cannot give";
}

TEST_F(FfEffectPlayerTest, AnUpdateReachesTheNextPlay) {
    ASSERT_EQ(upload(rumble(0x4000, 0, 0), 0), 0);
    ASSERT_EQ(upload(rumble(0xffff, 0, 0), 0), 0);
    EXPECT_EQ(effects.effects(), 1u);
    effects.play(0, 1);
    EXPECT_TRUE(drove(1.0, 0));
}

}  // namespace
}  // namespace vibscore::daemon
