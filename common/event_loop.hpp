#pragma once

#include <systemd/sd-event.h>

#include <cstdint>
#include <functional>
#include <memory>

// The timers' deadlines are on monotonic_now_us(), the clock every deadline in the daemon uses.
#include "common/monotonic_clock.hpp"

namespace sdbus {
class IConnection;
}

namespace vibscore::daemon {

struct EventSourceUnref {
    void operator()(sd_event_source* source) const { sd_event_source_disable_unref(source); }
};
using EventSourcePtr = std::unique_ptr<sd_event_source, EventSourceUnref>;

// One thread's loop: the bus thread's serves the bus, its timers and signals; the playback
// thread has its own for the player's timer (PlaybackThread). A loop is used by one thread only.
class EventLoop {
  public:
    // The service manager's watchdog is pinged by daemon/watchdog.*, which knows whether both
    // threads are alive; a loop never pings by itself.
    EventLoop();
    ~EventLoop();
    EventLoop(const EventLoop&) = delete;
    EventLoop& operator=(const EventLoop&) = delete;

    sd_event* get() const { return event_; }

    // Runs until exit(); returns the code given to it.
    int run();
    void exit(int code);

    // A one-shot timer on CLOCK_MONOTONIC with microsecond accuracy, re-armed at will.
    class Timer {
      public:
        Timer(EventLoop& loop, std::function<void()> fire);
        // Fires at the absolute time `at_us` (monotonic_now_us() scale); replaces any earlier arm.
        void arm(std::uint64_t at_us);
        void disarm();
        bool armed() const;

      private:
        static int dispatch(sd_event_source*, std::uint64_t, void* self);
        std::function<void()> fire_;
        EventSourcePtr source_;
    };

    // Calls `handler` when `signo` arrives (the signal is blocked for the thread first).
    EventSourcePtr on_signal(int signo, std::function<void()> handler);

  private:
    sd_event* event_ = nullptr;
    std::vector<std::unique_ptr<std::function<void()>>> signal_handlers_;
};

// Serves an sdbus-c++ connection from the loop: its fd and timeout become loop sources, refreshed
// before every wait, so bus calls are handled in the same thread as timers.
class BusLoopBinding {
  public:
    BusLoopBinding(EventLoop& loop, sdbus::IConnection& connection);
    BusLoopBinding(const BusLoopBinding&) = delete;
    BusLoopBinding& operator=(const BusLoopBinding&) = delete;

  private:
    static int on_io(sd_event_source*, int, std::uint32_t, void* self);
    static int on_time(sd_event_source*, std::uint64_t, void* self);
    static int on_prepare(sd_event_source*, void* self);
    void process();

    sdbus::IConnection& connection_;
    EventSourcePtr io_;
    EventSourcePtr timer_;
    EventSourcePtr wake_;  // sdbus-c++ 2's event fd; none with 1.x
};

}  // namespace vibscore::daemon
