#pragma once

#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "daemon/event_loop.hpp"
#include "daemon/player.hpp"
#include "daemon/task_queue.hpp"

namespace vibscore::daemon {

// The player on a thread of its own, with its own sd-event loop and timer, so that nothing the
// bus thread does (parsing and rendering a score, registry I/O, bus traffic) can delay a cue.
// Every actuator call happens on this thread. The bus thread hands it work with call() and
// waits for the answer; what the player reports comes back through an eventfd in the bus
// thread's loop, where the listener hears of it (sdbus-c++ is used from the bus thread only).
// docs/daemon.md, Threads.
class PlaybackThread {
  public:
    struct Options {
        std::uint64_t first_id = 1;  // the player's first playback id
        // 1..99 asks for SCHED_FIFO at that priority, quietly falling back to normal
        // scheduling without the privilege; 0 never asks.
        int rt_priority = 0;
    };

    // Starts the thread and the player on it, driving `actuator` (which must outlive this).
    // Events are delivered in `bus_loop`, the loop of the thread that constructs this.
    PlaybackThread(EventLoop& bus_loop, drivers::Actuator& actuator, const Options& options);
    PlaybackThread(EventLoop& bus_loop, drivers::Actuator& actuator)
        : PlaybackThread(bus_loop, actuator, Options{}) {}
    // Ends the thread; the player switches the actuator off as it goes.
    ~PlaybackThread();
    PlaybackThread(const PlaybackThread&) = delete;
    PlaybackThread& operator=(const PlaybackThread&) = delete;

    // Runs `work(player)` on the playback thread and returns what it returns, or throws what it
    // throws. What the player reported meanwhile has reached the listener when this returns.
    // Only from the bus thread; `work` may use the bus thread's data (it waits), but not the bus.
    template <typename Work>
    auto call(Work&& work) -> std::invoke_result_t<Work&, Player&> {
        using Result = std::invoke_result_t<Work&, Player&>;
        std::packaged_task<Result()> task([&] { return work(*player_); });
        auto result = task.get_future();
        post([&task] { task(); });
        result.wait();
        deliver();
        return result.get();
    }

    // Who hears of playback events, on the bus thread; nullptr: nobody.
    void set_listener(PlayerListener* listener) { listener_ = listener; }

    // Runs `task` on the bus thread with the next events: for what happens on the playback
    // thread that the bus must hear of (the actuator host's switches).
    void to_bus(std::function<void()> task);

    // Whether the thread got SCHED_FIFO.
    bool realtime() const { return realtime_; }

  private:
    class Relay;

    void run(drivers::Actuator& actuator, const Options& options, std::promise<void>& started);
    void post(std::function<void()> work);
    void deliver();

    PlayerListener* listener_ = nullptr;  // bus thread only
    TaskQueue work_;                      // for the playback thread
    TaskQueue events_;                    // for the bus thread
    EventSourcePtr events_source_;        // in the bus loop

    // The playback thread's; set before the constructor returns, used only on that thread.
    EventLoop* loop_ = nullptr;
    Player* player_ = nullptr;
    bool realtime_ = false;
    std::thread thread_;
};

}  // namespace vibscore::daemon
