#include "daemon/playback_thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/log.hpp"

namespace vibscore::daemon {

// On the playback thread: each thing the player reports becomes a task for the bus thread.
class PlaybackThread::Relay final : public PlayerListener {
  public:
    explicit Relay(PlaybackThread& thread) : thread_(thread) {}

    void playback_started(std::uint64_t id, const std::string& label) override {
        thread_.to_bus([&thread = thread_, id, label] {
            if (thread.listener_ != nullptr) {
                thread.listener_->playback_started(id, label);
            }
        });
    }
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override {
        thread_.to_bus([&thread = thread_, id, bar, symbol] {
            if (thread.listener_ != nullptr) {
                thread.listener_->playback_position(id, bar, symbol);
            }
        });
    }
    void playback_finished(std::uint64_t id, const std::string& reason) override {
        thread_.to_bus([&thread = thread_, id, reason] {
            if (thread.listener_ != nullptr) {
                thread.listener_->playback_finished(id, reason);
            }
        });
    }

  private:
    PlaybackThread& thread_;
};

PlaybackThread::PlaybackThread(EventLoop& bus_loop, drivers::Actuator& actuator,
                               const Options& options)
    : bus_thread_(std::this_thread::get_id()), call_timeout_(options.call_timeout) {
    sd_event_source* source = nullptr;
    const int result = sd_event_add_io(
        bus_loop.get(), &source, events_.fd(), EPOLLIN,
        [](sd_event_source*, int, std::uint32_t, void* self) {
            static_cast<PlaybackThread*>(self)->deliver();
            return 0;
        },
        this);
    if (result < 0) {
        throw std::runtime_error(std::string("sd_event_add_io for playback events: ") +
                                 std::strerror(-result));
    }
    events_source_.reset(source);

    std::promise<void> started;
    auto ready = started.get_future();
    thread_ = std::thread([&] { run(actuator, options, started); });
    try {
        ready.get();
    } catch (...) {
        thread_.join();
        throw;
    }
    if (options.rt_priority > 0) {
        sched_param param{};
        param.sched_priority = options.rt_priority;
        const int refused = ::pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &param);
        realtime_ = refused == 0;
        if (refused != 0) {
            // Normal scheduling is what most development machines give; it works, less punctually.
            log::debug("playback thread runs at normal priority: SCHED_FIFO " +
                       std::to_string(options.rt_priority) + " refused: " + std::strerror(refused));
        }
    }
}

PlaybackThread::~PlaybackThread() {
    post([this] { loop_->exit(0); });
    // A thread stuck in a driver would never join: after the call timeout the process ends
    // without it (the kernel closes the devices; the unit's ExecStopPost switches the actuator
    // off), rather than hanging until the service manager kills it.
    const auto deadline = std::chrono::steady_clock::now() + call_timeout_;
    while (!ended_ && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (!ended_) {
        log::error("the playback thread did not end within " +
                   std::to_string(call_timeout_.count()) + " ms; exiting without it");
        std::_Exit(EXIT_FAILURE);
    }
    thread_.join();
}

void PlaybackThread::run(drivers::Actuator& actuator, const Options& options,
                         std::promise<void>& started) {
    // Without SCHED_FIFO the kernel may defer each wake-up by the timer slack (50 µs by default)
    // to batch it with others. Best effort.
    ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
    std::optional<EventLoop> loop;
    std::optional<Relay> relay;
    std::optional<Player> player;
    EventSourcePtr work_source;
    try {
        loop.emplace();
        relay.emplace(*this);
        player.emplace(*loop, actuator, &*relay, options.first_id);
        sd_event_source* source = nullptr;
        const int result = sd_event_add_io(
            loop->get(), &source, work_.fd(), EPOLLIN,
            [](sd_event_source*, int, std::uint32_t, void* self) {
                static_cast<PlaybackThread*>(self)->work_.run_all();
                return 0;
            },
            this);
        if (result < 0) {
            throw std::runtime_error(std::string("sd_event_add_io for playback work: ") +
                                     std::strerror(-result));
        }
        work_source.reset(source);
        loop_ = &*loop;
        player_ = &*player;
    } catch (...) {
        started.set_exception(std::current_exception());
        return;
    }
    started.set_value();
    try {
        loop->run();
    } catch (const std::exception& error) {
        log::error(std::string("playback thread: ") + error.what());
    }
    // Whatever ended the loop, no call will be answered any more: say so at once.
    ended_ = true;
}

std::shared_ptr<const BusProperties> PlaybackThread::properties() const {
    const std::lock_guard lock(properties_mutex_);
    return properties_;
}

void PlaybackThread::publish(const std::function<void(BusProperties&)>& change) {
    if (thread_.get_id() != std::this_thread::get_id()) {
        throw std::logic_error(
            "PlaybackThread::publish() is only for the playback thread, the "
            "one writer of the properties");
    }
    // Only this thread writes, so the copy taken here is still the current one when it is
    // swapped in; readers keep whichever copy they took.
    auto changed = std::make_shared<BusProperties>(*properties());
    change(*changed);
    const std::lock_guard lock(properties_mutex_);
    properties_ = std::move(changed);
}

void PlaybackThread::require_bus_thread() const {
    if (std::this_thread::get_id() == bus_thread_) {
        return;
    }
    const bool playback = thread_.get_id() == std::this_thread::get_id();
    throw std::logic_error(std::string("PlaybackThread::call() is only for the bus thread, which "
                                       "made the PlaybackThread; it was called from ") +
                           (playback ? "the playback thread itself, where it would wait for "
                                       "itself"
                                     : "another thread"));
}

void PlaybackThread::submit(const std::shared_ptr<TaskBase>& task) {
    if (ended_) {
        throw PlaybackStuck(
            "the playback thread has ended (see the log); vibscored must be "
            "restarted");
    }
    if (stuck_) {
        const std::lock_guard lock(stuck_->mutex);
        if (stuck_->state != TaskBase::State::done) {
            throw PlaybackStuck(
                "the playback thread is still stuck in an earlier call (a driver "
                "that does not return?); the watchdog restarts vibscored");
        }
        stuck_.reset();
    }
    post([this, task] {
        {
            const std::lock_guard lock(task->mutex);
            if (task->state == TaskBase::State::abandoned) {
                task->state = TaskBase::State::done;  // its caller gave up: nothing to run
                return;
            }
            task->state = TaskBase::State::running;
        }
        task->run(*player_);
        {
            const std::lock_guard lock(task->mutex);
            task->state = TaskBase::State::done;
        }
        task->finished.notify_all();
    });
    std::unique_lock lock(task->mutex);
    const bool done = task->finished.wait_for(lock, call_timeout_,
                                              [&] { return task->state == TaskBase::State::done; });
    if (done) {
        return;
    }
    if (task->state == TaskBase::State::queued) {
        task->state = TaskBase::State::abandoned;
    }
    // Until the thread gets past this task, calls fail at once instead of each waiting.
    stuck_ = task;
    throw PlaybackStuck("the playback thread did not answer within " +
                        std::to_string(call_timeout_.count()) +
                        " ms (a driver that does not return?); the watchdog restarts vibscored "
                        "unless it recovers");
}

void PlaybackThread::ask_for_heartbeat() {
    post([this] { heartbeat_us_ = monotonic_now_us(); });
}

bool PlaybackThread::answered_since(std::uint64_t since_us) const {
    return heartbeat_us_.load() >= since_us;
}

void PlaybackThread::post(std::function<void()> work) {
    work_.push(std::move(work));
}

void PlaybackThread::to_bus(std::function<void()> task) {
    events_.push(std::move(task));
}

void PlaybackThread::deliver() {
    events_.run_all();
}

}  // namespace vibscore::daemon
