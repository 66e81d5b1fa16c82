#include "daemon/drivers/pwm_thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <time.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <utility>

#include "common/log.hpp"
#include "common/monotonic_clock.hpp"

namespace vibscore::drivers {

namespace {

constexpr std::int64_t kNanosPerSecond = 1'000'000'000;

void sleep_until(std::int64_t deadline_ns) {
    // A late thread goes straight on: the edge is due, and a system call would only add to it.
    if (monotonic_now_ns() >= deadline_ns) {
        return;
    }
    const timespec deadline{static_cast<time_t>(deadline_ns / kNanosPerSecond),
                            static_cast<long>(deadline_ns % kNanosPerSecond)};
    while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
    }
}

// The start of the period after the one that started at `start`. When the thread is more than a
// period late, whole periods are skipped (keeping the phase) instead of being played in a burst.
std::int64_t next_period_start(std::int64_t start, std::int64_t period) {
    std::int64_t next = start + period;
    const std::int64_t behind = monotonic_now_ns() - next;
    if (behind > period) {
        next += behind / period * period;
    }
    return next;
}

}  // namespace

PwmThread::PwmThread(std::unique_ptr<GpioLines> lines, int rt_priority)
    : lines_(std::move(lines)), all_low_(lines_->count(), 0), written_(all_low_) {
    thread_ = std::thread([this] { run(); });
    if (rt_priority > 0) {
        realtime_ = set_realtime(rt_priority);
    }
}

PwmThread::~PwmThread() {
    {
        const std::lock_guard lock(mutex_);
        quit_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

bool PwmThread::set_realtime(int priority) {
    sched_param param{};
    param.sched_priority = priority;
    const int result = ::pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &param);
    if (result == 0) {
        return true;
    }
    // Every reload makes a new thread; saying it once is enough.
    static std::atomic_flag warned = ATOMIC_FLAG_INIT;
    if (!warned.test_and_set()) {
        log::warning(lines_->describe() + ": PWM thread runs at normal priority: SCHED_FIFO " +
                     std::to_string(priority) + " refused: " + std::strerror(result) +
                     " (needs CAP_SYS_NICE or LimitRTPRIO=); edges will be less punctual");
    }
    return false;
}

void PwmThread::play(PwmWaveform waveform) {
    {
        const std::lock_guard lock(mutex_);
        pending_ = std::move(waveform);
    }
    wake_.notify_one();
}

std::optional<std::string> PwmThread::take_error() {
    const std::lock_guard lock(mutex_);
    return std::exchange(error_, std::nullopt);
}

bool PwmThread::write(std::unique_lock<std::mutex>& lock, const std::vector<int>& values) {
    if (values == written_) {
        return true;
    }
    // The kernel call runs unlocked so that play() never waits for it.
    lock.unlock();
    std::string failure;
    try {
        lines_->set_values(values);
        written_ = values;
    } catch (const std::exception& error) {
        failure = error.what();
    } catch (...) {
        failure = lines_->describe() + ": unknown error";
    }
    lock.lock();
    if (failure.empty()) {
        return true;
    }
    fail(lock, failure);
    return false;
}

void PwmThread::fail(std::unique_lock<std::mutex>& lock, const std::string& message) {
    if (!error_) {
        error_ = message;
    }
    // Whatever was handed over meanwhile waits for the next play(), which learns of the error.
    pending_.reset();
    lock.unlock();
    written_.clear();
    try {
        lines_->set_values(all_low_);
        written_ = all_low_;
    } catch (...) {
        // Already reported: the first error is the one the caller hears of.
    }
    lock.lock();
}

void PwmThread::run() {
    // Without SCHED_FIFO the kernel may defer each wake-up by the timer slack (50 µs by
    // default) to batch it with others: too much for a 1 ms carrier. Best effort.
    ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
    std::unique_lock lock(mutex_);
    PwmWaveform playing;  // steady low
    std::size_t next_edge = 0;
    std::int64_t period_start = 0;
    // After a line error fail() has tried every line low once; writing again before the next
    // play() would only report the same error a second time.
    bool failed = false;
    while (!quit_) {
        if (playing.steady() && pending_) {
            // Nothing is running: the new waveform starts now.
            playing = std::move(*pending_);
            pending_.reset();
            next_edge = 0;
            period_start = monotonic_now_ns();
            failed = false;
        }
        if (playing.steady()) {
            if (!failed &&
                !write(lock, playing.edges.empty() ? all_low_ : playing.edges.front().values)) {
                playing = {};
                failed = true;
            }
            wake_.wait(lock, [this] { return quit_ || pending_; });
            continue;
        }
        const std::int64_t deadline = period_start + playing.edges[next_edge].at_ns;
        lock.unlock();
        sleep_until(deadline);
        lock.lock();
        if (quit_) {
            break;
        }
        if (pending_ && (pending_->steady() || next_edge == 0)) {
            playing = std::move(*pending_);
            pending_.reset();
            next_edge = 0;
            period_start = deadline;
            failed = false;
            if (playing.steady()) {
                continue;
            }
        }
        if (!write(lock, playing.edges[next_edge].values)) {
            playing = {};
            failed = true;
            continue;
        }
        if (++next_edge == playing.edges.size()) {
            next_edge = 0;
            period_start = next_period_start(period_start, playing.period_ns);
        }
    }
    lock.unlock();
    try {
        if (written_ != all_low_) {
            lines_->set_values(all_low_);
        }
    } catch (const std::exception& error) {
        log::warning(std::string(error.what()) + " (driving the lines low at shutdown)");
    }
}

}  // namespace vibscore::drivers
