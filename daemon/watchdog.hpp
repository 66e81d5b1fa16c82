#pragma once

#include <cstdint>

#include "common/event_loop.hpp"
#include "daemon/playback_thread.hpp"

namespace vibscore::daemon {

// The service manager's watchdog (the unit's WatchdogSec=, passed as WATCHDOG_USEC): pinged from
// the bus thread's loop, and only while the playback thread answers as well, so that a daemon
// with either thread stuck (a driver that never returns, a loop that ended) stops pinging and
// systemd restarts it. Without WATCHDOG_USEC it does nothing.
class Watchdog {
  public:
    Watchdog(EventLoop& bus_loop, PlaybackThread& playback);
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

    bool enabled() const { return interval_us_ != 0; }

  private:
    void tick();

    PlaybackThread& playback_;
    std::uint64_t interval_us_ = 0;  // WATCHDOG_USEC
    std::uint64_t asked_us_ = 0;     // when the playback thread was last asked to answer
    bool warned_ = false;
    EventLoop::Timer timer_;
};

}  // namespace vibscore::daemon
