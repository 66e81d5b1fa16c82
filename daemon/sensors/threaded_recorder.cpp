#include "daemon/sensors/threaded_recorder.hpp"

#include <utility>

namespace vibscore::sensors {

ThreadedRecorder::~ThreadedRecorder() {
    halt();
}

void ThreadedRecorder::halt() {
    stopping_ = true;
    if (thread_.joinable()) {
        thread_.join();
    }
    if (begun_) {
        begun_ = false;
        end();
    }
}

void ThreadedRecorder::start() {
    halt();
    readings_.clear();
    failure_ = nullptr;
    stopping_ = false;
    try {
        begin();
    } catch (...) {
        end();
        throw;
    }
    begun_ = true;
    thread_ = std::thread([this] {
        try {
            while (!stopping_) {
                read_some(readings_);
            }
            // Once more after stop() was asked: what the device had taken by then, still on its
            // way (a scan in the buffer, an event not yet read), belongs to the recording.
            read_some(readings_);
        } catch (...) {
            failure_ = std::current_exception();
        }
    });
}

std::vector<Reading> ThreadedRecorder::stop() {
    halt();
    if (failure_) {
        std::rethrow_exception(std::exchange(failure_, nullptr));
    }
    return std::exchange(readings_, {});
}

}  // namespace vibscore::sensors
