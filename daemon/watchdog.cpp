#include "daemon/watchdog.hpp"

#include <systemd/sd-daemon.h>

#include <string>

#include "common/log.hpp"

namespace vibscore::daemon {

Watchdog::Watchdog(EventLoop& bus_loop, PlaybackThread& playback)
    : playback_(playback), timer_(bus_loop, [this] { tick(); }) {
    std::uint64_t interval_us = 0;
    if (sd_watchdog_enabled(0, &interval_us) > 0) {
        interval_us_ = interval_us;
        tick();
    }
}

// Four ticks a period: the playback thread is asked each time and must have answered the
// previous ask (a quarter of the period later) for the ping to go out. systemd gives up after
// a whole period without one.
void Watchdog::tick() {
    const std::uint64_t now = monotonic_now_us();
    if (asked_us_ == 0 || playback_.answered_since(asked_us_)) {
        sd_notify(0, "WATCHDOG=1");
        if (warned_) {
            log::info("the playback thread answers again");
            warned_ = false;
        }
    } else if (!warned_) {
        log::error("the playback thread has not answered for " +
                   std::to_string((now - asked_us_) / 1000) +
                   " ms (a driver that does not return?); the service manager's watchdog is no "
                   "longer pinged, so systemd restarts vibscored unless it answers");
        warned_ = true;
    }
    asked_us_ = now;
    playback_.ask_for_heartbeat();
    timer_.arm(now + interval_us_ / 4);
}

}  // namespace vibscore::daemon
