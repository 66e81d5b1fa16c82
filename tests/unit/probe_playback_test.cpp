// The calibration's probe as a playback (PlaybackRequest::probe, daemon/calibrator.*): its drives
// reach the backend as the plan wrote them, whatever the declared actuator, the intensities and
// the rated drive would make of a score's strengths; still within full scale and the backend's
// reverse capability.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "daemon/player.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

class Recorder : public drivers::Actuator {
  public:
    std::string_view driver_name() const override { return "recorder"; }
    drivers::Capabilities capabilities() const override { return can; }
    void apply(const drivers::Drive& drive) override { applied.push_back(drive); }
    void off() noexcept override { ++offs; }
    void set_gain(double gain) override { gains.push_back(gain); }
    std::vector<drivers::Drive> applied;
    std::vector<double> gains;
    int offs = 0;
    drivers::Capabilities can{.frequency_control = true, .reverse = true};
};

class Quiet : public PlayerListener {
  public:
    explicit Quiet(EventLoop& loop) : loop_(loop) {}
    void playback_started(std::uint64_t, const std::string&) override {}
    void playback_position(std::uint64_t, std::size_t, std::size_t) override {}
    void playback_finished(std::uint64_t, const std::string& why) override {
        reason = why;
        loop_.exit(0);
    }
    std::string reason;

  private:
    EventLoop& loop_;
};

render::Cue drive(double at, double amplitude, double frequency) {
    return render::drive_at(at, amplitude, frequency);
}

PlaybackRequest probe(bool is_probe) {
    PlaybackRequest request;
    request.label = "<calibration>";
    request.cues = std::make_shared<render::CueList>(
        std::vector<render::Cue>{drive(0.0, 1.0, 160.0), drive(0.003, -1.0, 160.0),
                                 drive(0.006, 1.5, 180.0), drive(0.009, 0.0, 0.0)});
    request.duration_s = 0.012;
    request.usage = Usage::hardware_feedback;
    request.intensity = 0.5;
    request.probe = is_probe;
    return request;
}

actuator::Declaration declared_lra() {
    actuator::Declaration declared;
    declared.kind = actuator::Kind::lra;
    declared.rated_drive = 0.6;
    declared.brake = actuator::Brake::reverse;
    return declared;
}

// The plan's drives as the backend gets them: the last (0) is the player's off().
const std::vector<drivers::Drive> kAsWritten{{1.0, 160.0}, {-1.0, 160.0}, {1.0, 180.0}};

TEST(ProbePlayback, DrivesReachTheBackendAsWrittenClampedToFullScaleWithoutCompensation) {
    EventLoop loop;
    Recorder actuator;
    Quiet listener(loop);
    Player player(loop, actuator, listener);
    player.set_actuator(declared_lra());
    player.set_master_intensity(0.3);
    const int offs = actuator.offs;
    player.play(probe(true));
    loop.run();
    EXPECT_EQ(listener.reason, "completed");
    EXPECT_EQ(actuator.applied, kAsWritten);
    EXPECT_GT(actuator.offs, offs);
}

TEST(ProbePlayback, ABackendThatCannotReverseGetsNothingBelowZero) {
    EventLoop loop;
    Recorder actuator;
    actuator.can.reverse = false;
    Quiet listener(loop);
    Player player(loop, actuator, listener);
    player.play(probe(true));
    loop.run();
    EXPECT_EQ(actuator.applied,
              (std::vector<drivers::Drive>{{1.0, 160.0}, {1.0, 180.0}}));  // -1: off instead
}

TEST(ProbePlayback, WithGainTheDeviceIsSetToFullScaleForTheProbe) {
    EventLoop loop;
    Recorder actuator;
    actuator.can.gain_control = true;
    Quiet listener(loop);
    Player player(loop, actuator, listener);
    player.set_master_intensity(0.3);
    actuator.gains.clear();
    player.play(probe(true));
    loop.run();
    EXPECT_THAT(actuator.gains, ::testing::ElementsAre(1.0));
}

TEST(ProbePlayback, TheSameCuesAsAScoreAreShapedAndScaledAsUsual) {
    // What the probe flag changes: without it the declared actuator's planner, the rated drive
    // and the intensity shape the drives.
    EventLoop loop;
    Recorder actuator;
    Quiet listener(loop);
    Player player(loop, actuator, listener);
    player.set_actuator(declared_lra());
    player.play(probe(false));
    loop.run();
    ASSERT_FALSE(actuator.applied.empty());
    EXPECT_NE(actuator.applied, kAsWritten);
}

}  // namespace
}  // namespace vibscore::daemon
