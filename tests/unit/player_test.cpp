#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gmock/gmock.h>

#include <algorithm>
#include <limits>

#include "daemon/play_request.hpp"
#include "daemon/player.hpp"
#include "daemon/strength_scale.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using render::Cue;

struct Applied {
    std::uint64_t at_us;
    drivers::Drive drive;
};

class RecordingActuator : public drivers::Actuator {
  public:
    std::string_view driver_name() const override { return "recording"; }
    drivers::Capabilities capabilities() const override { return capabilities_; }
    void apply(const drivers::Drive& drive) override {
        if (fail_after >= 0 && static_cast<int>(applied.size()) >= fail_after) {
            throw drivers::DeviceError("/dev/fake: No such device");
        }
        applied.push_back({monotonic_now_us(), drive});
    }
    void off() noexcept override { applied.push_back({monotonic_now_us(), {}}); }
    void prepare(const drivers::Drive& next) override { prepared.push_back(next); }
    void set_off_timer(double seconds) override { off_timers.push_back(seconds); }
    void set_gain(double gain) override {
        if (fail_gain) {
            throw drivers::DeviceError("/dev/fake: gain: No such device");
        }
        gains.push_back(gain);
    }
    std::vector<Applied> applied;
    std::vector<drivers::Drive> prepared;
    std::vector<double> gains;
    std::vector<double> off_timers;
    int fail_after = -1;
    bool fail_gain = false;
    drivers::Capabilities capabilities_{.frequency_control = true};
};

class RecordingListener : public PlayerListener {
  public:
    explicit RecordingListener(EventLoop& loop) : loop_(loop) {}
    void playback_started(std::uint64_t id, const std::string& label) override {
        events.push_back("started " + std::to_string(id) + " " + label);
    }
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override {
        events.push_back("position " + std::to_string(id) + " " + std::to_string(bar) + "." +
                         std::to_string(symbol));
        position_times_us.push_back(monotonic_now_us());
    }
    void playback_finished(std::uint64_t id, const std::string& reason) override {
        events.push_back("finished " + std::to_string(id) + " " + reason);
        if (exit_on_finish) {
            loop_.exit(0);
        }
    }
    std::vector<std::string> events;
    std::vector<std::uint64_t> position_times_us;
    bool exit_on_finish = true;

  private:
    EventLoop& loop_;
};

Cue drive(double at, double amplitude, double frequency = 0.0) {
    Cue cue;
    cue.at = at;
    cue.amplitude = amplitude;
    cue.frequency_hz = frequency;
    return cue;
}

Cue position(double at, std::size_t bar, std::size_t symbol) {
    Cue cue;
    cue.at = at;
    cue.kind = Cue::Kind::position;
    cue.bar = bar;
    cue.symbol = symbol;
    return cue;
}

std::shared_ptr<const render::CueSource> cue_list(std::vector<Cue> cues) {
    return std::make_shared<render::CueList>(std::move(cues));
}

PlaybackRequest request(Usage usage = Usage::notification, int repeat = 0, uid_t owner = 1000) {
    PlaybackRequest request;
    request.label = "tacton";
    request.cues = cue_list({drive(0, 0.5, 170), position(0, 0, 0), drive(0.004, 0.8, 200),
                             position(0.004, 0, 1), drive(0.008, 0)});
    request.duration_s = 0.01;
    request.usage = usage;
    request.repeat = repeat;
    request.owner = owner;
    request.sender = ":1.7";
    return request;
}

class PlayerTest : public ::testing::Test {
  protected:
    EventLoop loop;
    RecordingActuator actuator;
    RecordingListener listener{loop};
    Player player{loop, actuator, listener};
};

TEST_F(PlayerTest, TheActuatorIsOffFromTheStart) {
    ASSERT_EQ(actuator.applied.size(), 1u);
    EXPECT_EQ(actuator.applied[0].drive.amplitude, 0.0);
}

TEST_F(PlayerTest, PlaysEveryCueInOrderNeverEarlyThenCompletes) {
    actuator.applied.clear();
    const std::uint64_t before = monotonic_now_us();
    const auto id = player.play(request());
    ASSERT_EQ(actuator.applied.size(), 1u) << "first drive before play() returns";
    EXPECT_EQ(actuator.applied[0].drive, (drivers::Drive{0.5, 170}));
    loop.run();
    EXPECT_EQ(listener.events,
              (std::vector<std::string>{"started 1 tacton", "position 1 0.0", "position 1 0.1",
                                        "finished 1 completed"}));
    ASSERT_GE(actuator.applied.size(), 3u);
    EXPECT_EQ(actuator.applied[1].drive, (drivers::Drive{0.8, 200}));
    EXPECT_GE(actuator.applied[1].at_us, before + 4000);
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
    EXPECT_EQ(id, 1u);
    EXPECT_FALSE(player.current_id());
}

TEST_F(PlayerTest, RepeatsTheWholeScoreTheAskedNumberOfTimesMore) {
    player.play(request(Usage::ringtone, 2));
    loop.run();
    EXPECT_EQ(std::count_if(actuator.applied.begin(), actuator.applied.end(),
                            [](const Applied& applied) {
                                return applied.drive == drivers::Drive{0.5, 170};
                            }),
              3);
    EXPECT_EQ(listener.events.back(), "finished 1 completed");
}

TEST_F(PlayerTest, IntensityScalesAndIsClampedToFullDrive) {
    actuator.applied.clear();
    auto loud = request();
    loud.intensity = 0.5;
    player.set_master_intensity(0.5);
    player.play(loud);
    EXPECT_DOUBLE_EQ(actuator.applied[0].drive.amplitude, 0.125);
    player.stop(0, 1000, false);
    auto over = request();
    over.cues = cue_list({drive(0, 7.0, 170), position(0, 0, 0), drive(0.004, 0.8, 200),
                          position(0.004, 0, 1), drive(0.008, 0)});
    player.set_master_intensity(1.0);
    player.play(over);
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 1.0);
}

TEST_F(PlayerTest, AMoreImportantRequestPreemptsALessImportantOne) {
    player.play(request(Usage::touch));
    actuator.applied.clear();
    const auto alarm = player.play(request(Usage::alarm));
    EXPECT_EQ(listener.events.at(2), "finished 1 preempted");
    EXPECT_EQ(actuator.applied.at(0).drive.amplitude, 0.0) << "off between the two";
    EXPECT_EQ(player.current_id(), alarm);
}

TEST_F(PlayerTest, ALessImportantRequestIsRefused) {
    player.play(request(Usage::alarm));
    EXPECT_THROW(player.play(request(Usage::notification)), PlayerBusy);
    EXPECT_EQ(player.current_id(), 1u);
}

TEST_F(PlayerTest, AnEquallyImportantRequestTakesOver) {
    player.play(request(Usage::notification));
    player.play(request(Usage::notification));
    EXPECT_EQ(listener.events.at(2), "finished 1 preempted");
    EXPECT_EQ(player.current_id(), 2u);
}

TEST_F(PlayerTest, ARepeatingPlaybackKeepsItsTurnAgainstAnEqualOneShot) {
    player.play(request(Usage::ringtone, -1));
    EXPECT_THROW(player.play(request(Usage::ringtone, 0)), PlayerBusy);
    player.play(request(Usage::ringtone, -1));  // another ringtone replaces it
    EXPECT_EQ(player.current_id(), 2u);
}

TEST_F(PlayerTest, AdmissionIsAnsweredWithoutPlayingAsPlayWouldAnswer) {
    EXPECT_NO_THROW(player.check_admission(Usage::touch, 0));  // nothing plays
    player.play(request(Usage::alarm, -1));
    const auto driven = actuator.applied.size();
    EXPECT_THROW(player.check_admission(Usage::notification, 0), PlayerBusy);
    EXPECT_THROW(player.check_admission(Usage::alarm, 0), PlayerBusy);
    EXPECT_NO_THROW(player.check_admission(Usage::alarm, -1));
    EXPECT_NO_THROW(player.check_admission(Usage::ringtone, 0));
    EXPECT_EQ(actuator.applied.size(), driven);
    EXPECT_EQ(player.current_id(), 1u);
}

TEST_F(PlayerTest, CommunicationAndAccessibilityAreEquallyImportant) {
    player.play(request(Usage::accessibility));
    player.play(request(Usage::communication));
    EXPECT_EQ(player.current_id(), 2u);
    EXPECT_THROW(player.play(request(Usage::hardware_feedback)), PlayerBusy);
    EXPECT_EQ(importance(Usage::touch), importance(Usage::media));
}

TEST_F(PlayerTest, StopSilencesAtOnceAndReportsStopped) {
    const auto id = player.play(request(Usage::ringtone, -1));
    actuator.applied.clear();
    EXPECT_EQ(player.stop(id, 1000, false), Player::StopResult::stopped);
    ASSERT_EQ(actuator.applied.size(), 1u);
    EXPECT_EQ(actuator.applied[0].drive.amplitude, 0.0);
    EXPECT_EQ(listener.events.back(), "finished 1 stopped");
    EXPECT_EQ(player.stop(id, 1000, false), Player::StopResult::not_playing);
    EXPECT_EQ(player.stop(99, 1000, false), Player::StopResult::not_found);
}

TEST_F(PlayerTest, AnIdThisPlayerNeverGaveOutIsNotFound) {
    Player later_run{loop, actuator, &listener, (std::uint64_t{3} << 32) + 1};
    const auto id = later_run.play(request(Usage::ringtone, -1));
    EXPECT_EQ(id, (std::uint64_t{3} << 32) + 1);
    EXPECT_EQ(later_run.stop(1, 1000, true), Player::StopResult::not_found);
    EXPECT_EQ(later_run.stop((std::uint64_t{2} << 32) + 1, 1000, true),
              Player::StopResult::not_found);
    EXPECT_EQ(later_run.current_id(), id);
    EXPECT_EQ(later_run.stop(id, 1000, false), Player::StopResult::stopped);
}

TEST_F(PlayerTest, OnlyTheOwnerOrAPrivilegedCallerMayStop) {
    const auto id = player.play(request(Usage::ringtone, -1, 1000));
    EXPECT_EQ(player.stop(id, 1001, false), Player::StopResult::not_permitted);
    EXPECT_EQ(player.stop(0, 1001, false), Player::StopResult::not_playing);
    EXPECT_EQ(player.current_id(), id);
    EXPECT_EQ(player.stop(id, 0, true), Player::StopResult::stopped);
}

TEST_F(PlayerTest, StopZeroStopsWhatTheCallerHasPlaying) {
    player.play(request(Usage::ringtone, -1, 1000));
    EXPECT_EQ(player.stop(0, 1000, false), Player::StopResult::stopped);
}

TEST_F(PlayerTest, AnEndlessPlaybackEndsWhenItsCallerLeavesTheBus) {
    player.play(request(Usage::ringtone, -1));
    player.sender_vanished(":1.99");
    EXPECT_TRUE(player.current_id());
    player.sender_vanished(":1.7");
    EXPECT_EQ(listener.events.back(), "finished 1 client-vanished");
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
}

// A repeating playback `repeat` more times of one-drive passes `duration_s` long.
PlaybackRequest passes(int repeat, double duration_s) {
    auto repeating = request(Usage::notification, repeat);
    repeating.cues = cue_list({drive(0, 0.5, 170), position(0, 0, 0), drive(duration_s * 0.8, 0)});
    repeating.duration_s = duration_s;
    return repeating;
}

TEST_F(PlayerTest, ARepeatingPlaybackThatEndsWithinTheBoundOutlivesItsCaller) {
    // 3000 passes of 10 ms: 30 s, the longest a playback plays on without its caller.
    ASSERT_EQ(kPlaysOnWithoutItsCaller_s, 30.0);
    player.play(passes(2999, 0.010));
    player.sender_vanished(":1.7");
    EXPECT_TRUE(player.current_id());
    EXPECT_THAT(listener.events,
                ::testing::Not(::testing::Contains(::testing::StartsWith("finished"))));
}

TEST_F(PlayerTest, ARepeatingPlaybackThatWouldOutlastTheBoundEndsWhenItsCallerLeaves) {
    // One pass more, 30.01 s: the first that ends with its caller, as repeat 2147483647 does.
    player.play(passes(3000, 0.010));
    player.sender_vanished(":1.99");
    EXPECT_TRUE(player.current_id()) << "another caller left";
    player.sender_vanished(":1.7");
    EXPECT_EQ(listener.events.back(), "finished 1 client-vanished");
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
    player.play(passes(std::numeric_limits<int>::max(), 0.010));
    player.sender_vanished(":1.7");
    EXPECT_EQ(listener.events.back(), "finished 2 client-vanished");
}

TEST_F(PlayerTest, StoppingEveryPlaybackEndsAnyonesAndSaysWhichItEnded) {
    EXPECT_TRUE(player.stop_every_playback().empty()) << "nothing plays";
    const auto id = player.play(request(Usage::ringtone, -1, 65534));
    actuator.applied.clear();
    EXPECT_EQ(player.stop_every_playback(), std::vector<std::uint64_t>{id});
    EXPECT_EQ(listener.events.back(), "finished 1 stopped");
    ASSERT_EQ(actuator.applied.size(), 1u);
    EXPECT_EQ(actuator.applied[0].drive.amplitude, 0.0);
    EXPECT_FALSE(player.current_id());
    EXPECT_TRUE(player.stop_every_playback().empty());
}

// Issue 27: positions were reported at every note and rest, thousands a second.
TEST_F(PlayerTest, PositionsAreReportedAtMostFiftyTimesASecondEndingWithTheLastOne) {
    std::vector<Cue> cues{drive(0, 0.5, 170)};
    for (std::size_t i = 0; i < 500; ++i) {
        cues.push_back(position(static_cast<double>(i) * 0.001, 0, i));  // one every 1 ms
    }
    cues.push_back(drive(0.5, 0));
    auto dense = request();
    dense.cues = cue_list(cues);
    dense.duration_s = 0.5;
    player.play(dense);
    loop.run();
    const auto& times = listener.position_times_us;
    ASSERT_GE(times.size(), 2u);
    EXPECT_LE(times.size(), 0.5 * 50 + 2) << "at most 50 a second, and one as it ends";
    // The listener reads the clock a little after the player did: up to 1 ms of it.
    for (std::size_t i = 1; i + 1 < times.size(); ++i) {
        EXPECT_GE(times[i] - times[i - 1] + 1000, kPositionReportInterval_us) << i;
    }
    EXPECT_EQ(listener.events.at(1), "position 1 0.0") << "the first at once";
    EXPECT_EQ(listener.events.at(listener.events.size() - 2), "position 1 0.499");
    EXPECT_EQ(listener.events.back(), "finished 1 completed");
}

TEST_F(PlayerTest, AHeldPositionIsReportedWhenItsIntervalEndsNotAtTheNextCue) {
    // Two positions 1 ms apart, then a long rest: the second must not wait for the rest's end.
    auto sparse = request();
    sparse.cues = cue_list({drive(0, 0.5, 170), position(0, 0, 0), position(0.001, 0, 1),
                            drive(0.3, 0), position(0.3, 0, 2)});
    sparse.duration_s = 0.31;
    const auto started = monotonic_now_us();
    player.play(sparse);
    loop.run();
    ASSERT_EQ(listener.position_times_us.size(), 3u);
    EXPECT_EQ(listener.events.at(2), "position 1 0.1");
    EXPECT_GE(listener.position_times_us[1], started + kPositionReportInterval_us);
    EXPECT_LT(listener.position_times_us[1], started + 200'000) << "long before the rest ends";
}

// Issue 27: an inline clef of tempo 0.001 and 2,000 rests, repeated until stopped, made the daemon
// report 8,000 positions a second, on and on.
TEST_F(PlayerTest, AScoreAskingForMoreCuesASecondThanAPlaybackMayRunEndsWithLimitExceeded) {
    std::string rests;
    for (int i = 0; i < 2000; ++i) {
        rests += "<Rest length=\"32th\"/>";
    }
    const ScoreToPlay flood{
        vibscore::testing::bundle_from(
            vibscore::testing::one_clef_score("<Bar clef=\"c\"><Note length=\"32th\" number=\"1\" "
                                              "string=\"1\"/>" +
                                              rests + "</Bar>"),
            {{"c.xml", vibscore::testing::sine_clef(0.001, {170}, {1.0})}}),
        "<inline>"};
    PlayOptions options;
    options.repeat = -1;
    const auto started = monotonic_now_us();
    EventLoop::Timer give_up(loop, [this] { loop.exit(0); });  // it would flood on for ever
    give_up.arm(started + 2'000'000);
    player.play(make_playback_request(flood, options, 0.030));
    loop.run();
    EXPECT_THAT(listener.events.back(),
                ::testing::StartsWith("finished 1 limit-exceeded: the score asks for more than "
                                      "1000 actuator commands and positions a second"));
    EXPECT_LT(monotonic_now_us() - started, 1'000'000u);
    EXPECT_LE(listener.position_times_us.size(), 12u);
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
}

TEST_F(PlayerTest, AFiniteRepeatKeepsItsTurnAgainstAnEqualOneShotUntilItsLastPass) {
    // Three passes of 100 ms; an equally important one-shot asks in each of them.
    player.play(passes(2, 0.100));
    std::vector<bool> admitted;
    const auto started = monotonic_now_us();
    std::optional<EventLoop::Timer> asking;
    int asked = 0;
    asking.emplace(loop, [&] {
        try {
            player.check_admission(Usage::notification, 0);
            admitted.push_back(true);
        } catch (const PlayerBusy&) {
            admitted.push_back(false);
        }
        if (++asked < 3) {
            asking->arm(started + 50'000 + static_cast<std::uint64_t>(asked) * 100'000);
        }
    });
    asking->arm(started + 50'000);
    loop.run();
    EXPECT_EQ(admitted, (std::vector<bool>{false, false, true}));
    EXPECT_EQ(listener.events.back(), "finished 1 completed");
}

TEST_F(PlayerTest, APlaybackThatEndsByItselfOutlivesItsCaller) {
    player.play(request(Usage::notification, 1));
    player.sender_vanished(":1.7");
    EXPECT_TRUE(player.current_id());
    loop.run();
    EXPECT_EQ(listener.events.back(), "finished 1 completed");
}

TEST_F(PlayerTest, ADeviceErrorEndsThePlaybackWithItsReason) {
    actuator.fail_after = 2;
    player.play(request());
    loop.run();
    EXPECT_EQ(listener.events.back(), "finished 1 device-error: /dev/fake: No such device");
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
}

TEST_F(PlayerTest, AGainTheDeviceRefusesAtPlayEndsThePlaybackNotTheCall) {
    actuator.capabilities_ = {.frequency_control = true, .gain_control = true};
    actuator.fail_gain = true;
    actuator.applied.clear();
    const auto id = player.play(request());
    EXPECT_EQ(id, 1u);
    EXPECT_FALSE(player.current_id());
    EXPECT_EQ(listener.events.back(), "finished 1 device-error: /dev/fake: gain: No such device");
    for (const auto& applied : actuator.applied) {
        EXPECT_EQ(applied.drive.amplitude, 0.0);  // nothing but off
    }
}

TEST_F(PlayerTest, ReplacingTheActuatorStopsPlaybackAndSwitchesBothOff) {
    player.play(request(Usage::ringtone, -1));
    RecordingActuator other;
    player.replace_actuator(other);
    EXPECT_EQ(listener.events.back(), "finished 1 stopped");
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
    ASSERT_EQ(other.applied.size(), 1u);
    EXPECT_EQ(other.applied[0].drive.amplitude, 0.0);
    player.replace_actuator(actuator);  // `other` dies before the player does
}

TEST_F(PlayerTest, AnOnOffActuatorFeelsStrengthAsPulseWidth) {
    actuator.capabilities_ = {.amplitude_control = false};
    actuator.applied.clear();
    auto half = request();
    half.cues = cue_list({drive(0, 0.5), drive(0.2, 0)});
    half.duration_s = 0.2;
    player.play(half);
    loop.run();
    // 40 ms periods from the onset, each on (full drive) for 20 ms.
    std::vector<double> on_starts;
    for (const auto& applied : actuator.applied) {
        EXPECT_TRUE(applied.drive.amplitude == 0.0 || applied.drive.amplitude == 1.0);
        if (applied.drive.amplitude == 1.0) {
            on_starts.push_back(static_cast<double>(applied.at_us));
        }
    }
    EXPECT_EQ(on_starts.size(), 5u);
}

// [actuator]: an ERM rated at 0.7 of full scale that may be braked backwards.
actuator::Declaration rated_erm(bool compensation) {
    actuator::Declaration declared;
    declared.kind = actuator::Kind::erm;
    declared.rated_drive = 0.7;
    declared.brake = actuator::Brake::reverse;
    declared.compensation = compensation;
    return declared;
}

PlaybackRequest one_note() {
    auto note = request();
    note.cues = cue_list({drive(0, 1.0), drive(0.1, 0)});
    note.duration_s = 0.1;
    return note;
}

std::vector<double> amplitudes(const std::vector<Applied>& applied) {
    std::vector<double> values;
    for (const auto& a : applied) {
        values.push_back(a.drive.amplitude);
    }
    return values;
}

TEST_F(PlayerTest, ADeclaredActuatorIsOverdrivenHeldAndBrakedWhereItCan) {
    actuator.capabilities_ = {.reverse = true};
    player.set_actuator(rated_erm(true));
    actuator.applied.clear();
    player.play(one_note());
    loop.run();
    // Full scale, the rated drive, full scale backwards, off (and off again at the end).
    EXPECT_THAT(amplitudes(actuator.applied), ::testing::ElementsAre(1.0, 0.7, -1.0, 0.0, 0.0));
}

TEST_F(PlayerTest, ABackendThatCannotReverseIsNeverDrivenBackwards) {
    player.set_actuator(rated_erm(true));
    actuator.applied.clear();
    player.play(one_note());
    loop.run();
    for (const double amplitude : amplitudes(actuator.applied)) {
        EXPECT_GE(amplitude, 0.0);
    }
    EXPECT_EQ(actuator.applied.front().drive.amplitude, 1.0);
}

TEST_F(PlayerTest, WithADeclarationStrengthOneIsTheRatedDriveAndIntensityScalesIt) {
    player.set_actuator(rated_erm(false));
    actuator.applied.clear();
    auto soft = one_note();
    soft.intensity = 0.5;
    player.play(soft);
    EXPECT_DOUBLE_EQ(actuator.applied[0].drive.amplitude, 0.35);
    player.stop(0, 1000, false);
    player.set_actuator(std::nullopt);  // as written again
    player.play(one_note());
    EXPECT_DOUBLE_EQ(actuator.applied.back().drive.amplitude, 1.0);
}

TEST_F(PlayerTest, AGainCapableActuatorTakesTheMasterIntensityAsItsGain) {
    actuator.capabilities_ = {.frequency_control = true, .gain_control = true};
    actuator.applied.clear();
    player.set_master_intensity(0.5);
    auto soft = request();
    soft.intensity = 0.5;
    player.play(soft);
    ASSERT_FALSE(actuator.gains.empty());
    EXPECT_EQ(actuator.gains.back(), 0.5);
    EXPECT_DOUBLE_EQ(actuator.applied[0].drive.amplitude, 0.25);  // the request's own 0.5 only
    player.stop(0, 1000, false);
}

TEST_F(PlayerTest, AnEffectMemoryActuatorGetsEachDriveBeforeItsOnset) {
    actuator.capabilities_ = {.frequency_control = true, .effect_memory = true};
    player.play(request());
    ASSERT_EQ(actuator.prepared.size(), 1u);
    EXPECT_EQ(actuator.prepared[0], (drivers::Drive{0.8, 200}));
    loop.run();
    EXPECT_EQ(actuator.prepared.size(), 1u);  // nothing after the last note
}

TEST_F(PlayerTest, AnActuatorIsHeldOffAfterItsMaximumOnTimeUntilTheScorePauses) {
    actuator.capabilities_ = {.frequency_control = true, .max_on_time_s = 0.02};
    actuator.applied.clear();
    auto long_note = request();
    // 60 ms on (two notes, tied), a pause, then a new note that may drive again.
    long_note.cues = cue_list({drive(0, 0.5, 170), drive(0.03, 0.6, 170), drive(0.06, 0),
                               drive(0.07, 0.7, 170), drive(0.08, 0)});
    long_note.duration_s = 0.09;
    player.play(long_note);
    loop.run();
    std::vector<double> amplitudes;
    for (const auto& applied : actuator.applied) {
        amplitudes.push_back(applied.drive.amplitude);
    }
    // On, cut off at 20 ms, the tied 0.6 withheld, then the note after the pause plays.
    EXPECT_EQ(amplitudes, (std::vector<double>{0.5, 0.0, 0.0, 0.7, 0.0, 0.0}));
    ASSERT_GE(actuator.applied.size(), 2u);
    const auto on_us = actuator.applied[1].at_us - actuator.applied[0].at_us;
    EXPECT_GE(on_us, 20'000u);
}

TEST_F(PlayerTest, AKernelTimerIsArmedWithTheTimeUntilTheScoreSwitchesOff) {
    actuator.capabilities_ = {.off_timer = true};
    player.play(request());  // on at 0, stronger at 4 ms, off at 8 ms
    loop.run();
    ASSERT_EQ(actuator.off_timers.size(), 2u) << "one for each drive that switches on";
    EXPECT_GT(actuator.off_timers[0], 0.004);
    EXPECT_LE(actuator.off_timers[0], 0.008);
    EXPECT_LE(actuator.off_timers[1], 0.004);
}

TEST_F(PlayerTest, TheFirstKernelTimerCountsFromTheFirstDriveNotFromTheCall) {
    // The hil guest saw the first note's timer armed 47 ms short: what the playback did before its
    // first drive (here a slow device taking its gain) was counted against the note.
    class SlowGainActuator : public RecordingActuator {
      public:
        void set_gain(double gain) override {
            vibscore::testing::pace_for(std::chrono::milliseconds(30));  // the slow device
            RecordingActuator::set_gain(gain);
        }
    };
    SlowGainActuator slow;
    slow.capabilities_ = {.gain_control = true, .off_timer = true};
    RecordingListener slow_listener(loop);
    Player slow_player{loop, slow, slow_listener};
    slow_player.play(request());  // on at 0, stronger at 4 ms, off at 8 ms
    loop.run();
    ASSERT_EQ(slow.gains.size(), 1u);
    ASSERT_EQ(slow.off_timers.size(), 2u);
    EXPECT_GT(slow.off_timers[0], 0.004);
    EXPECT_LE(slow.off_timers[0], 0.008);
}

TEST_F(PlayerTest, AKernelTimerIsNeverArmedPastTheMaximumOnTime) {
    actuator.capabilities_ = {.max_on_time_s = 0.002, .off_timer = true};
    player.play(request());
    ASSERT_FALSE(actuator.off_timers.empty());
    EXPECT_EQ(actuator.off_timers[0], 0.002);
    player.stop(0, 1000, false);
}

// Issue 33, row 2: a stranger's `repeat -1` notification held the actuator for as long as its
// process lived. The limit is counted from the start, across every pass.
TEST_F(PlayerTest, ARepeatingPlaybackEndsAtItsMaximumOnTimeWithLimitExceeded) {
    auto endless = passes(-1, 0.010);
    endless.max_on_time_s = 0.1;
    const auto started = monotonic_now_us();
    player.play(endless);
    loop.run();
    const auto ended = monotonic_now_us();
    EXPECT_EQ(listener.events.back(),
              "finished 1 limit-exceeded: played for its maximum on-time of 0.1 s ([limits] "
              "max-on-time)");
    EXPECT_GE(ended - started, 100'000u) << "not before its limit";
    EXPECT_LT(ended - started, 1'000'000u);
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
    EXPECT_FALSE(player.current_id());
}

// Issue 33, row 3: a fire-and-forget one-shot of 14 whole notes drove the actuator for 56 minutes
// after its caller had left.
TEST_F(PlayerTest, AFireAndForgetOneShotIsBoundedLikeAnyOther) {
    auto long_one = request();
    long_one.cues = cue_list({drive(0, 0.5, 170), drive(3600, 0)});
    long_one.duration_s = 3600;
    long_one.max_on_time_s = 0.05;
    player.play(long_one);
    player.sender_vanished(":1.7");
    EXPECT_TRUE(player.current_id()) << "a one-shot plays on without its caller";
    loop.run();
    EXPECT_THAT(listener.events.back(), ::testing::StartsWith("finished 1 limit-exceeded: played"));
    EXPECT_EQ(actuator.applied.back().drive.amplitude, 0.0);
}

TEST_F(PlayerTest, AScoreExactlyAsLongAsItsMaximumOnTimeCompletes) {
    auto exact = request();
    exact.cues = cue_list({drive(0, 0.5, 170), drive(0.05, 0)});
    exact.duration_s = 0.05;
    exact.max_on_time_s = 0.05;
    player.play(exact);
    loop.run();
    EXPECT_EQ(listener.events.back(), "finished 1 completed");
}

TEST_F(PlayerTest, AUserCutOffByTheLimitMayNotRepeatAtOnceButMayPlayAOneShot) {
    auto endless = passes(-1, 0.010);
    endless.max_on_time_s = 0.03;
    player.play(endless);
    loop.run();
    ASSERT_THAT(listener.events.back(), ::testing::HasSubstr("limit-exceeded"));
    EXPECT_THROW(player.check_cool_down(1000, Usage::notification, -1, 10.0), CoolingDown);
    EXPECT_NO_THROW(player.check_cool_down(1000, Usage::notification, 0, 10.0));
    EXPECT_NO_THROW(player.check_cool_down(1001, Usage::notification, -1, 10.0));
}

TEST_F(PlayerTest, AUserWhosePlaybackWasStoppedByStopAllMayNotRepeatAtOnce) {
    player.play(request(Usage::touch, -1, 1001));
    player.stop_every_playback();
    EXPECT_THROW(player.check_cool_down(1001, Usage::touch, 2, 10.0), CoolingDown);
    EXPECT_NO_THROW(player.check_cool_down(1001, Usage::alarm, -1, 10.0)) << "urgent";
}

TEST_F(PlayerTest, AUsersOwnStopStartsNoCoolDown) {
    player.play(request(Usage::notification, -1));
    ASSERT_EQ(player.stop(0, 1000, false), Player::StopResult::stopped);
    EXPECT_NO_THROW(player.check_cool_down(1000, Usage::notification, -1, 10.0));
}

// Issue 33, row 4: each new playback began with a fresh position interval, so a stream of short
// Plays sent 111 positions a second. The bound is per connection across its playbacks.
TEST_F(PlayerTest, AStreamOfShortPlaysFromOneConnectionGetsAtMost50PositionsASecond) {
    listener.exit_on_finish = false;
    const auto started = monotonic_now_us();
    for (int i = 0; i < 200; ++i) {
        player.play(request(Usage::touch));  // each preempts the one before
    }
    const double elapsed_s = static_cast<double>(monotonic_now_us() - started) / 1e6;
    const auto positions = listener.position_times_us.size();
    EXPECT_GE(positions, 2u);
    EXPECT_LE(static_cast<double>(positions),
              static_cast<double>(kPositionBurstPerConnection) +
                  static_cast<double>(kPositionsPerSecondPerConnection) * elapsed_s)
        << positions << " positions in " << elapsed_s << " s";
}

TEST_F(PlayerTest, ShortPlaysFromManyConnectionsAreBoundedInTotal) {
    listener.exit_on_finish = false;
    const auto started = monotonic_now_us();
    for (int i = 0; i < 300; ++i) {
        auto short_one = request(Usage::touch);
        short_one.sender = ":1." + std::to_string(i % 10);
        player.play(short_one);
    }
    const double elapsed_s = static_cast<double>(monotonic_now_us() - started) / 1e6;
    const auto positions = listener.position_times_us.size();
    EXPECT_GE(positions, static_cast<std::size_t>(kPositionBurstInTotal));
    EXPECT_LE(static_cast<double>(positions),
              static_cast<double>(kPositionBurstInTotal) +
                  static_cast<double>(kPositionsPerSecondInTotal) * elapsed_s)
        << positions << " positions in " << elapsed_s << " s";
}

// The one decision play() and every drive share: who carries the master Intensity.
TEST(StrengthScale, WithoutGainTheStrengthsCarryBothIntensities) {
    drivers::Capabilities plain;
    plain.gain_control = false;
    plain.amplitude_control = true;
    const auto scale = strength_scale(plain, 0.5, 0.4, false);
    EXPECT_DOUBLE_EQ(scale.software, 0.2);
    EXPECT_FALSE(scale.device_gain.has_value());
}

TEST(StrengthScale, AGainCapableAmplitudeBackendTakesTheMasterAsItsGain) {
    drivers::Capabilities gain;
    gain.gain_control = true;
    gain.amplitude_control = true;
    const auto scale = strength_scale(gain, 0.5, 0.4, false);
    EXPECT_DOUBLE_EQ(scale.software, 0.5);
    ASSERT_TRUE(scale.device_gain.has_value());
    EXPECT_DOUBLE_EQ(*scale.device_gain, 0.4);
}

// Pulses at full drive are scaled by the device's gain too: the master in the duty as well
// would be felt squared (0.4 x 0.4).
TEST(StrengthScale, PulsesOnAGainBackendLeaveTheMasterToTheGainAndAProbeDrivesAtFullScaleAndGain) {
    drivers::Capabilities pulses;
    pulses.gain_control = true;
    pulses.amplitude_control = false;
    const auto scale = strength_scale(pulses, 0.5, 0.4, false);
    EXPECT_DOUBLE_EQ(scale.software, 0.5);
    ASSERT_TRUE(scale.device_gain.has_value());
    EXPECT_DOUBLE_EQ(*scale.device_gain, 0.4);
    drivers::Capabilities plain_pulses;
    plain_pulses.gain_control = false;
    plain_pulses.amplitude_control = false;
    EXPECT_DOUBLE_EQ(strength_scale(plain_pulses, 0.5, 0.4, false).software, 0.2);
    const auto probe = strength_scale(pulses, 0.5, 0.4, true);
    EXPECT_DOUBLE_EQ(probe.software, 1.0);
    ASSERT_TRUE(probe.device_gain.has_value());
    EXPECT_DOUBLE_EQ(*probe.device_gain, 1.0);
}

}  // namespace
}  // namespace vibscore::daemon
