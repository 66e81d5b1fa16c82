#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/event_loop.hpp"
#include "daemon/bus_properties.hpp"
#include "daemon/player.hpp"
#include "daemon/task_queue.hpp"

namespace vibscore::daemon {

// The playback thread did not answer in time (a driver is stuck in the kernel, say), or is gone:
// what call() throws instead of waiting on. The bus adaptor sends it as the Device error.
class PlaybackStuck : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The player on a thread of its own, with its own sd-event loop and timer, so that nothing the
// bus thread does (parsing and rendering a score, registry I/O, bus traffic) can delay a cue.
// Every actuator call happens on this thread. The bus thread hands it work with call() and
// waits for the answer, for at most call_timeout(): a stuck playback thread must not take the
// bus with it. What the player reports comes back through an eventfd in the bus thread's loop,
// where the listener hears of it (sdbus-c++ is used from the bus thread only).
// docs/daemon.md, Threads.
class PlaybackThread {
  public:
    struct Options {
        std::uint64_t first_id = 1;  // the player's first playback id
        // 1..99 asks for SCHED_FIFO at that priority, quietly falling back to normal
        // scheduling without the privilege; 0 never asks.
        int rt_priority = 0;
        // How long call() waits: far longer than anything the player does (microseconds, a
        // driver's open a few ms), far shorter than a D-Bus caller's patience (25 s).
        std::chrono::milliseconds call_timeout{2000};
    };

    // Starts the thread and the player on it, driving `actuator` (which must outlive this).
    // Events are delivered in `bus_loop`, the loop of the thread that constructs this: the bus
    // thread, the only one that may call().
    PlaybackThread(EventLoop& bus_loop, drivers::Actuator& actuator, const Options& options);
    PlaybackThread(EventLoop& bus_loop, drivers::Actuator& actuator)
        : PlaybackThread(bus_loop, actuator, Options{}) {}
    // Ends the thread; the player switches the actuator off as it goes.
    ~PlaybackThread();
    PlaybackThread(const PlaybackThread&) = delete;
    PlaybackThread& operator=(const PlaybackThread&) = delete;

    // Runs `work(player)` on the playback thread and returns what it returns, or throws what it
    // throws. What the player reported meanwhile has reached the listener when this returns.
    // Only from the bus thread (std::logic_error otherwise: from the playback thread it would
    // wait for itself). Throws PlaybackStuck when the thread does not answer within the call
    // timeout, has not yet finished a call that timed out, or has ended; then `work` may still
    // run later, or never, so it must own what it uses (capture by value, or objects that live
    // as long as the daemon).
    template <typename Work>
    auto call(Work work) -> std::invoke_result_t<Work&, Player&> {
        using Result = std::invoke_result_t<Work&, Player&>;
        require_bus_thread();
        if constexpr (std::is_void_v<Result>) {
            call([work = std::move(work)](Player& player) mutable {
                work(player);
                return true;
            });
        } else {
            auto task = std::make_shared<Task<Result>>();
            task->work = [work = std::move(work)](Player& player) mutable -> Result {
                return work(player);
            };
            submit(task);
            deliver();
            return task->take();
        }
    }

    // Who hears of playback events, on the bus thread; nullptr: nobody.
    void set_listener(PlayerListener* listener) { listener_ = listener; }

    // Runs `task` on the bus thread with the next events: for what happens on the playback
    // thread that the bus must hear of (the actuator host's switches).
    void to_bus(std::function<void()> task);

    // Whether the thread got SCHED_FIFO.
    bool realtime() const { return realtime_; }

    // The properties last published: from any thread, without waiting for the playback thread
    // (which may be stuck in a driver). Never null; all defaults until the first publish.
    std::shared_ptr<const BusProperties> properties() const;
    // Publishes `change` applied to a copy of the current properties. Only on the playback
    // thread (in a call's work, or what that work runs): the one writer, so changes never race
    // (std::logic_error otherwise).
    void publish(const std::function<void(BusProperties&)>& change);

    // For the service manager's watchdog (daemon/watchdog.*): asks the playback thread to show
    // it is alive, without waiting; answered_since() says whether it has done so since `since_us`
    // (monotonic_now_us() scale).
    void ask_for_heartbeat();
    bool answered_since(std::uint64_t since_us) const;

  private:
    class Relay;

    // One call's work and result, shared by both threads: whichever of them is late finds the
    // other's part done (or abandoned) and leaves.
    struct TaskBase {
        enum class State { queued, running, done, abandoned };
        virtual ~TaskBase() = default;
        virtual void run(Player& player) = 0;
        std::mutex mutex;
        std::condition_variable finished;
        State state = State::queued;
    };
    template <typename Result>
    struct Task final : TaskBase {
        std::function<Result(Player&)> work;
        std::optional<Result> value;
        std::exception_ptr error;
        void run(Player& player) override {
            try {
                value.emplace(work(player));
            } catch (...) {
                error = std::current_exception();
            }
        }
        Result take() {
            if (error) {
                std::rethrow_exception(error);
            }
            return std::move(*value);
        }
    };

    void run(drivers::Actuator& actuator, const Options& options, std::promise<void>& started);
    void require_bus_thread() const;
    // Hands `task` to the playback thread and waits for it within the call timeout.
    void submit(const std::shared_ptr<TaskBase>& task);
    void post(std::function<void()> work);
    void deliver();

    PlayerListener* listener_ = nullptr;  // bus thread only
    TaskQueue work_;                      // for the playback thread
    TaskQueue events_;                    // for the bus thread
    EventSourcePtr events_source_;        // in the bus loop
    std::thread::id bus_thread_;
    std::chrono::milliseconds call_timeout_;
    // A call that timed out while its work ran: the thread is stuck until it finishes.
    std::shared_ptr<TaskBase> stuck_;  // bus thread only
    std::atomic<bool> ended_{false};   // the playback loop ended (or failed)
    std::atomic<std::uint64_t> heartbeat_us_{0};
    mutable std::mutex properties_mutex_;  // held only to copy or swap the pointer
    std::shared_ptr<const BusProperties> properties_ = std::make_shared<const BusProperties>();

    // The playback thread's; set before the constructor returns, used only on that thread.
    EventLoop* loop_ = nullptr;
    Player* player_ = nullptr;
    bool realtime_ = false;
    std::thread thread_;
};

}  // namespace vibscore::daemon
