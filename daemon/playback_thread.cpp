#include "daemon/playback_thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "daemon/log.hpp"

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
                               const Options& options) {
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
        // The bus thread's loop pings the service manager's watchdog; this one must not hide
        // a bus thread that hangs.
        loop.emplace(EventLoop::Watchdog::not_pinged);
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
