#pragma once

#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "daemon/sensors/accelerometer.hpp"

namespace vibscore::sensors {

// The kernel readers' common part: start() prepares the device and runs a thread that reads it
// until stop(), which ends the thread, puts the device back and hands over the readings (or
// rethrows what the thread met).
class ThreadedRecorder : public Accelerometer {
  public:
    ~ThreadedRecorder() override;
    void start() final;
    std::vector<Reading> stop() final;

  protected:
    // On the caller's thread: set the device up for streaming (throws naming what failed).
    virtual void begin() = 0;
    // On the recording thread: read what there is (waiting at most a few tens of ms) and append
    // it to `readings`.
    virtual void read_some(std::vector<Reading>& readings) = 0;
    // On the caller's thread, after the thread ended, whatever happened: put the device back.
    // Must not throw.
    virtual void end() noexcept = 0;

  private:
    void halt();

    std::thread thread_;
    std::atomic<bool> stopping_{false};
    std::vector<Reading> readings_;  // the thread's until it is joined
    std::exception_ptr failure_;
    bool begun_ = false;
};

}  // namespace vibscore::sensors
