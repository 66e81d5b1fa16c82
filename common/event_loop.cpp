#include "common/event_loop.hpp"

#include <signal.h>
#include <sys/epoll.h>
#include <time.h>

#include "dbus/sdbus_compat.hpp"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/log.hpp"

namespace vibscore::daemon {

namespace {

void check(int result, const char* what) {
    if (result < 0) {
        throw std::runtime_error(std::string(what) + ": " + std::strerror(-result));
    }
}

}  // namespace

EventLoop::EventLoop() {
    check(sd_event_new(&event_), "sd_event_new");
}

EventLoop::~EventLoop() {
    sd_event_unref(event_);
}

int EventLoop::run() {
    const int result = sd_event_loop(event_);
    check(result, "sd_event_loop");
    return result;
}

void EventLoop::exit(int code) {
    sd_event_exit(event_, code);
}

EventLoop::Timer::Timer(EventLoop& loop, std::function<void()> fire) : fire_(std::move(fire)) {
    sd_event_source* source = nullptr;
    check(sd_event_add_time(loop.get(), &source, CLOCK_MONOTONIC,
                            std::numeric_limits<std::uint64_t>::max(), 1, &Timer::dispatch, this),
          "sd_event_add_time");
    source_.reset(source);
    sd_event_source_set_enabled(source, SD_EVENT_OFF);
}

void EventLoop::Timer::arm(std::uint64_t at_us) {
    check(sd_event_source_set_time(source_.get(), at_us), "sd_event_source_set_time");
    check(sd_event_source_set_enabled(source_.get(), SD_EVENT_ONESHOT), "arming a timer");
}

void EventLoop::Timer::disarm() {
    sd_event_source_set_enabled(source_.get(), SD_EVENT_OFF);
}

bool EventLoop::Timer::armed() const {
    int enabled = SD_EVENT_OFF;
    sd_event_source_get_enabled(source_.get(), &enabled);
    return enabled != SD_EVENT_OFF;
}

int EventLoop::Timer::dispatch(sd_event_source*, std::uint64_t, void* self) {
    auto* timer = static_cast<Timer*>(self);
    try {
        timer->fire_();
    } catch (const std::exception& error) {
        // The loop must outlive any one callback's failure.
        log::error(std::string("timer callback failed: ") + error.what());
    }
    return 0;
}

EventSourcePtr EventLoop::on_signal(int signo, std::function<void()> handler) {
    sigset_t mask;
    sigemptyset(&mask);
    sigaddset(&mask, signo);
    check(-pthread_sigmask(SIG_BLOCK, &mask, nullptr), "blocking a signal");
    signal_handlers_.push_back(std::make_unique<std::function<void()>>(std::move(handler)));
    sd_event_source* source = nullptr;
    check(sd_event_add_signal(
              event_, &source, signo,
              [](sd_event_source*, const signalfd_siginfo*, void* user) {
                  (*static_cast<std::function<void()>*>(user))();
                  return 0;
              },
              signal_handlers_.back().get()),
          "sd_event_add_signal");
    return EventSourcePtr(source);
}

BusLoopBinding::BusLoopBinding(EventLoop& loop, sdbus::IConnection& connection)
    : connection_(connection) {
    const auto poll = dbus::poll_data(connection_);
    sd_event_source* io = nullptr;
    check(sd_event_add_io(loop.get(), &io, poll.fd, static_cast<std::uint32_t>(poll.events),
                          &BusLoopBinding::on_io, this),
          "sd_event_add_io for the bus");
    io_.reset(io);
    check(sd_event_source_set_prepare(io, &BusLoopBinding::on_prepare), "bus prepare callback");
    sd_event_source* timer = nullptr;
    check(sd_event_add_time(loop.get(), &timer, CLOCK_MONOTONIC,
                            std::numeric_limits<std::uint64_t>::max(), 0, &BusLoopBinding::on_time,
                            this),
          "sd_event_add_time for the bus");
    timer_.reset(timer);
    sd_event_source_set_enabled(timer, SD_EVENT_OFF);
    // sdbus-c++ 2 signals this fd when work was queued from another thread; reading the bus
    // clears it.
    if (poll.event_fd >= 0) {
        sd_event_source* wake = nullptr;
        check(sd_event_add_io(loop.get(), &wake, poll.event_fd, EPOLLIN, &BusLoopBinding::on_io,
                              this),
              "sd_event_add_io for the bus's wake-up fd");
        wake_.reset(wake);
    }
}

void BusLoopBinding::process() {
    try {
        while (dbus::process_pending(connection_)) {
        }
    } catch (const sdbus::Error& error) {
        // The bus went away (its daemon stopped): nothing is left to serve. An exception must
        // not unwind through sd-event's C frames, so the loop ends with a failure instead.
        log::error("the bus connection failed: " + error.getMessage());
        sd_event_exit(sd_event_source_get_event(io_.get()), 1);
    }
}

int BusLoopBinding::on_io(sd_event_source*, int, std::uint32_t, void* self) {
    static_cast<BusLoopBinding*>(self)->process();
    return 0;
}

int BusLoopBinding::on_time(sd_event_source*, std::uint64_t, void* self) {
    static_cast<BusLoopBinding*>(self)->process();
    return 0;
}

// sd-bus changes what it waits for as messages queue up; ask it again before every wait.
int BusLoopBinding::on_prepare(sd_event_source*, void* self) {
    auto* binding = static_cast<BusLoopBinding*>(self);
    const auto poll = dbus::poll_data(binding->connection_);
    sd_event_source_set_io_events(binding->io_.get(), static_cast<std::uint32_t>(poll.events));
    if (!poll.deadline_us) {
        sd_event_source_set_enabled(binding->timer_.get(), SD_EVENT_OFF);
    } else {
        sd_event_source_set_time(binding->timer_.get(), *poll.deadline_us);
        sd_event_source_set_enabled(binding->timer_.get(), SD_EVENT_ONESHOT);
    }
    return 0;
}

}  // namespace vibscore::daemon
