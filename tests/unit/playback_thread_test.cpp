// The player on its own thread: cues fall due while the bus thread is busy, every actuator call
// happens on the playback thread, and what the player reports reaches the listener on the bus
// thread, Started before Play's call returns and Finished before Stop's.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "daemon/playback_thread.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::daemon {
namespace {

using namespace std::chrono_literals;

// Records drives from the playback thread; the test thread waits for them.
class SharedActuator : public drivers::Actuator {
  public:
    std::string_view driver_name() const override { return "shared"; }
    drivers::Capabilities capabilities() const override { return {}; }
    void apply(const drivers::Drive& drive) override { record(drive.amplitude); }
    void off() noexcept override { record(0.0); }

    // Waits until the actuator has been driven `count` times in all; false after `limit`.
    bool wait_for(std::size_t count, std::chrono::milliseconds limit) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, limit, [&] { return amplitudes_.size() >= count; });
    }
    std::vector<double> amplitudes() {
        const std::lock_guard lock(mutex_);
        return amplitudes_;
    }
    std::vector<std::thread::id> threads() {
        const std::lock_guard lock(mutex_);
        return threads_;
    }

  private:
    void record(double amplitude) noexcept {
        const std::lock_guard lock(mutex_);
        amplitudes_.push_back(amplitude);
        threads_.push_back(std::this_thread::get_id());
        changed_.notify_all();
    }

    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<double> amplitudes_;
    std::vector<std::thread::id> threads_;
};

class BusListener : public PlayerListener {
  public:
    explicit BusListener(EventLoop& loop) : loop_(loop) {}
    void playback_started(std::uint64_t id, const std::string& label) override {
        heard("started " + std::to_string(id) + " " + label);
    }
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override {
        heard("position " + std::to_string(id) + " " + std::to_string(bar) + "." +
              std::to_string(symbol));
    }
    void playback_finished(std::uint64_t id, const std::string& reason) override {
        heard("finished " + std::to_string(id) + " " + reason);
        loop_.exit(0);
    }
    std::vector<std::string> events;
    std::vector<std::thread::id> threads;

  private:
    void heard(std::string event) {
        events.push_back(std::move(event));
        threads.push_back(std::this_thread::get_id());
    }
    EventLoop& loop_;
};

render::Cue cue(double at, double amplitude, render::Cue::Kind kind = render::Cue::Kind::drive) {
    render::Cue cue;
    cue.at = at;
    cue.amplitude = amplitude;
    cue.kind = kind;
    return cue;
}

// A 10 ms note, then its position marks.
PlaybackRequest short_note(Usage usage = Usage::notification, int repeat = 0) {
    PlaybackRequest request;
    request.label = "tap";
    request.cues = std::make_shared<render::CueList>(std::vector<render::Cue>{
        cue(0, 0.5), cue(0, 0, render::Cue::Kind::position), cue(0.010, 0)});
    request.duration_s = 0.010;
    request.usage = usage;
    request.repeat = repeat;
    request.owner = 1000;
    return request;
}

class PlaybackThreadTest : public ::testing::Test {
  protected:
    EventLoop bus_loop;
    SharedActuator actuator;
    BusListener listener{bus_loop};
    PlaybackThread playback{bus_loop, actuator, {.first_id = 7, .rt_priority = 0}};

    void SetUp() override { playback.set_listener(&listener); }
    void TearDown() override { playback.set_listener(nullptr); }
};

TEST_F(PlaybackThreadTest, ANoteEndsOnTimeWhileTheBusThreadIsBusy) {
    playback.call([](Player& player) { return player.play(short_note()); });
    // This thread neither runs its loop nor calls in: as if it were parsing a large score.
    // The note's end (off, after the constructor's off and the note) comes all the same.
    ASSERT_TRUE(actuator.wait_for(3, 5000ms)) << "the note's end waited for the bus thread";
    const auto amplitudes = actuator.amplitudes();
    EXPECT_EQ(std::vector<double>(amplitudes.begin(), amplitudes.begin() + 3),
              (std::vector<double>{0.0, 0.5, 0.0}));
}

TEST_F(PlaybackThreadTest, EveryActuatorCallHappensOnThePlaybackThread) {
    playback.call([](Player& player) { return player.play(short_note()); });
    bus_loop.run();
    playback.call([](Player& player) { player.set_master_intensity(0.5); });
    const auto threads = actuator.threads();
    ASSERT_GE(threads.size(), 3u);
    for (const auto& thread : threads) {
        EXPECT_NE(thread, std::this_thread::get_id());
        EXPECT_EQ(thread, threads.front());
    }
}

TEST_F(PlaybackThreadTest, StartedIsHeardBeforePlayReturnsAndFinishedBeforeStopReturns) {
    const auto id =
        playback.call([](Player& player) { return player.play(short_note(Usage::ringtone, -1)); });
    EXPECT_EQ(id, 7u);
    ASSERT_FALSE(listener.events.empty());
    EXPECT_EQ(listener.events.front(), "started 7 tap");
    playback.call([](Player& player) { return player.stop(7, 1000, false); });
    EXPECT_EQ(listener.events.back(), "finished 7 stopped");
    for (const auto& thread : listener.threads) {
        EXPECT_EQ(thread, std::this_thread::get_id());
    }
}

TEST_F(PlaybackThreadTest, WhatThePlayerReportsLaterArrivesThroughTheBusLoop) {
    playback.call([](Player& player) { return player.play(short_note()); });
    bus_loop.run();  // until Finished
    EXPECT_EQ(listener.events, (std::vector<std::string>{"started 7 tap", "position 7 0.0",
                                                         "finished 7 completed"}));
    for (const auto& thread : listener.threads) {
        EXPECT_EQ(thread, std::this_thread::get_id());
    }
}

TEST_F(PlaybackThreadTest, WhatThePlayerThrowsReachesTheCaller) {
    playback.call([](Player& player) { return player.play(short_note(Usage::ringtone, -1)); });
    EXPECT_THROW(
        playback.call([](Player& player) { player.check_admission(Usage::notification, 0); }),
        PlayerBusy);
}

TEST(PlaybackThread, EndingTheThreadSwitchesTheActuatorOff) {
    EventLoop bus_loop;
    SharedActuator actuator;
    {
        PlaybackThread playback{bus_loop, actuator};
        playback.call([](Player& player) {
            auto endless = short_note(Usage::ringtone, -1);
            endless.cues = std::make_shared<render::CueList>(std::vector<render::Cue>{cue(0, 0.5)});
            return player.play(std::move(endless));
        });
        EXPECT_EQ(actuator.amplitudes().back(), 0.5);
    }
    EXPECT_EQ(actuator.amplitudes().back(), 0.0);
}

// Opens when the test says so: a driver that does not return until then.
class Gate {
  public:
    void wait() {
        std::unique_lock lock(mutex_);
        opened_.wait(lock, [&] { return open_; });
    }
    void open() {
        {
            const std::lock_guard lock(mutex_);
            open_ = true;
        }
        opened_.notify_all();
    }

  private:
    std::mutex mutex_;
    std::condition_variable opened_;
    bool open_ = false;
};

// An actuator whose apply() of the drive 0.6 hangs until the gate opens; hanging() says it has
// got there, so that tests wait for the hang rather than for a time it is likely by.
class HangingActuator : public SharedActuator {
  public:
    explicit HangingActuator(Gate& gate) : gate_(gate) {}
    void apply(const drivers::Drive& drive) override {
        if (drive.amplitude == 0.6) {
            hanging_ = true;
            gate_.wait();
        }
        SharedActuator::apply(drive);
    }
    bool hanging() const { return hanging_; }

  private:
    Gate& gate_;
    std::atomic<bool> hanging_{false};
};

// 0.5 at once, 0.6 from 20 ms (on the playback thread's timer, not in the call), off at 40 ms.
PlaybackRequest two_drives() {
    PlaybackRequest request = short_note();
    request.cues = std::make_shared<render::CueList>(
        std::vector<render::Cue>{cue(0, 0.5), cue(0.020, 0.6), cue(0.040, 0)});
    request.duration_s = 0.040;
    return request;
}

TEST(PlaybackThreadRule, ACallFromThePlaybackThreadItselfIsRefusedNamingTheRule) {
    EventLoop bus_loop;
    SharedActuator actuator;
    PlaybackThread playback{bus_loop, actuator};
    try {
        playback.call([&playback](Player&) { playback.call([](Player&) {}); });
        ADD_FAILURE() << "a call from the playback thread was run";
    } catch (const std::logic_error& error) {
        EXPECT_NE(std::string(error.what()).find("only for the bus thread"), std::string::npos);
        EXPECT_NE(std::string(error.what()).find("the playback thread itself"), std::string::npos)
            << error.what();
    }
}

TEST(PlaybackThreadRule, ACallFromAThirdThreadIsRefused) {
    EventLoop bus_loop;
    SharedActuator actuator;
    PlaybackThread playback{bus_loop, actuator};
    std::string refusal;
    std::thread([&] {
        try {
            playback.call([](Player&) {});
        } catch (const std::logic_error& error) {
            refusal = error.what();
        }
    }).join();
    EXPECT_NE(refusal.find("from another thread"), std::string::npos) << refusal;
}

// A work that hangs (a driver stuck in the kernel): the call gives up after the timeout, the
// next ones fail at once without being run, and once the thread is back calls work again.
TEST(PlaybackThreadStuck, CallsFailAfterTheTimeoutThenAtOnceUntilTheThreadIsBack) {
    EventLoop bus_loop;
    SharedActuator actuator;
    PlaybackThread playback{bus_loop, actuator, {.call_timeout = 100ms}};
    Gate gate;
    EXPECT_THROW(playback.call([&gate](Player&) { gate.wait(); }), PlaybackStuck);
    bool ran = false;
    EXPECT_THROW(playback.call([&ran](Player&) { ran = true; }), PlaybackStuck);
    gate.open();
    // The stuck work finishes; the thread answers again.
    EXPECT_TRUE(testing::wait_until([&] {
        try {
            return playback.call([](Player&) { return 42; }) == 42;
        } catch (const PlaybackStuck&) {
            return false;
        }
    }));
    EXPECT_EQ(playback.call([](Player&) { return 43; }), 43);
    EXPECT_FALSE(ran);
}

// The thread hangs in a cue's apply(), not in a call: a call queued behind it times out and,
// abandoned, is never run when the thread comes back.
TEST(PlaybackThreadStuck, AnAbandonedCallIsNeverRunLater) {
    EventLoop bus_loop;
    Gate gate;
    HangingActuator actuator(gate);
    PlaybackThread playback{bus_loop, actuator, {.call_timeout = 100ms}};
    playback.call([](Player& player) { return player.play(two_drives()); });
    ASSERT_TRUE(testing::wait_until([&] { return actuator.hanging(); }));
    bool ran = false;
    EXPECT_THROW(playback.call([&ran](Player&) { ran = true; }), PlaybackStuck);
    gate.open();
    EXPECT_TRUE(testing::wait_until([&] {
        try {
            playback.call([](Player&) {});
            return true;
        } catch (const PlaybackStuck&) {
            return false;
        }
    }));
    EXPECT_FALSE(ran);
}

TEST(PlaybackThreadWatchdog, AHeartbeatIsAnsweredWhileTheThreadRunsAndNotWhileItHangs) {
    EventLoop bus_loop;
    Gate gate;
    HangingActuator actuator(gate);
    PlaybackThread playback{bus_loop, actuator, {.call_timeout = 100ms}};
    auto asked = monotonic_now_us();
    playback.ask_for_heartbeat();
    EXPECT_TRUE(testing::wait_until([&] { return playback.answered_since(asked); }));
    playback.call([](Player& player) { return player.play(two_drives()); });
    ASSERT_TRUE(testing::wait_until([&] { return actuator.hanging(); }));
    asked = monotonic_now_us();
    playback.ask_for_heartbeat();
    // Hung in apply(), it cannot answer: 100 ms is only how long the test gives it to be wrong.
    EXPECT_FALSE(testing::wait_until([&] { return playback.answered_since(asked); }, 100ms));
    gate.open();
    EXPECT_TRUE(testing::wait_until([&] { return playback.answered_since(asked); }));
}

// The bus serves its properties from what the playback thread published (HapticsService's
// getters read properties()), so a property read answers while the thread hangs in a driver,
// where a call() gives up.
TEST(PlaybackThreadProperties, TheLastPublishedPropertiesAreReadWhileTheThreadHangs) {
    EventLoop bus_loop;
    Gate gate;
    HangingActuator actuator(gate);
    PlaybackThread playback{bus_loop, actuator, {.call_timeout = 100ms}};
    EXPECT_EQ(playback.properties()->intensity, 1.0);  // before any publish: the defaults
    // Published as the service does; the player's own master stays 1, so that the actuator
    // still sees the drive it hangs on (0.6).
    playback.call([&playback](Player&) {
        playback.publish([](BusProperties& properties) {
            properties.driver = "hanging";
            properties.intensity = 0.4;
        });
    });
    playback.call([](Player& player) { return player.play(two_drives()); });
    ASSERT_TRUE(testing::wait_until([&] { return actuator.hanging(); }));
    EXPECT_THROW(playback.call([](Player& player) { return player.master_intensity(); }),
                 PlaybackStuck);
    const auto properties = playback.properties();
    EXPECT_EQ(properties->driver, "hanging");
    EXPECT_EQ(properties->intensity, 0.4);
    gate.open();
    EXPECT_TRUE(testing::wait_until([&] {
        try {
            playback.call([](Player&) {});
            return true;
        } catch (const PlaybackStuck&) {
            return false;
        }
    }));
}

// One writer, the playback thread: a publish changes only what it touches, and a reader keeps
// the copy it took.
TEST(PlaybackThreadProperties, APublishChangesWhatItTouchesAndAReaderKeepsItsCopy) {
    EventLoop bus_loop;
    SharedActuator actuator;
    PlaybackThread playback{bus_loop, actuator};
    playback.call([&playback](Player&) {
        playback.publish([](BusProperties& properties) {
            properties.driver = "sim";
            properties.capabilities = {"amplitude-control"};
        });
    });
    const auto before = playback.properties();
    playback.call([&playback](Player&) {
        playback.publish([](BusProperties& properties) { properties.intensity = 0.25; });
    });
    EXPECT_EQ(before->intensity, 1.0);
    const auto after = playback.properties();
    EXPECT_EQ(after->intensity, 0.25);
    EXPECT_EQ(after->driver, "sim");
    EXPECT_EQ(after->capabilities, std::vector<std::string>{"amplitude-control"});
}

TEST(PlaybackThreadProperties, APublishFromAnotherThreadIsRefusedNamingTheRule) {
    EventLoop bus_loop;
    SharedActuator actuator;
    PlaybackThread playback{bus_loop, actuator};
    try {
        playback.publish([](BusProperties& properties) { properties.intensity = 0.5; });
        ADD_FAILURE() << "a publish from the bus thread was taken";
    } catch (const std::logic_error& error) {
        EXPECT_NE(std::string(error.what()).find("only for the playback thread"), std::string::npos)
            << error.what();
    }
    EXPECT_EQ(playback.properties()->intensity, 1.0);
}

}  // namespace
}  // namespace vibscore::daemon
