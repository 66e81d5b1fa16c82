#include "daemon/sensors/evdev_accelerometer.hpp"

#include <linux/input.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "daemon/sensors/threaded_recorder.hpp"

namespace vibscore::sensors {

namespace {

namespace fs = std::filesystem;

constexpr double kStandardGravity = 9.80665;
constexpr unsigned kAxes[3] = {ABS_X, ABS_Y, ABS_Z};

class EvdevAccelerometer final : public ThreadedRecorder {
  public:
    EvdevAccelerometer(fs::path node, std::shared_ptr<SensorIo> io)
        : node_(std::move(node)), io_(std::move(io)) {
        const auto device = io_->open_device(node_);
        if (!device->has_input_property(INPUT_PROP_ACCELEROMETER)) {
            throw std::runtime_error(node_.string() +
                                     ": not an accelerometer (no INPUT_PROP_ACCELEROMETER)");
        }
        for (int axis = 0; axis < 3; ++axis) {
            const auto info = device->abs_axis(kAxes[axis]);
            if (!info) {
                throw std::runtime_error(node_.string() + ": has no ABS_" + "XYZ"[axis] + " axis");
            }
            if (info->resolution <= 0) {
                throw std::runtime_error(node_.string() + ": ABS_" + "XYZ"[axis] +
                                         " gives no resolution (units per g), so its readings "
                                         "cannot be put in m/s\u00b2");
            }
            per_unit_[axis] = kStandardGravity / info->resolution;
        }
    }

    std::string describe() const override { return node_.string() + " (evdev)"; }

  private:
    void begin() override {
        partial_.clear();
        stream_ = io_->open_device(node_);
        stream_->use_monotonic_clock();
    }

    void read_some(std::vector<Reading>& readings) override {
        const auto bytes = stream_->read(std::chrono::milliseconds(50));
        partial_.insert(partial_.end(), bytes.begin(), bytes.end());
        std::size_t used = 0;
        while (partial_.size() - used >= sizeof(input_event)) {
            input_event event{};
            std::memcpy(&event, partial_.data() + used, sizeof event);
            used += sizeof event;
            if (event.type == EV_ABS) {
                for (int axis = 0; axis < 3; ++axis) {
                    if (event.code == kAxes[axis]) {
                        current_[axis] = event.value * per_unit_[axis];
                    }
                }
            } else if (event.type == EV_SYN && event.code == SYN_REPORT) {
                const std::int64_t t_ns =
                    static_cast<std::int64_t>(event.input_event_sec) * 1'000'000'000 +
                    static_cast<std::int64_t>(event.input_event_usec) * 1000;
                readings.push_back({t_ns, current_[0], current_[1], current_[2]});
            }
        }
        partial_.erase(partial_.begin(), partial_.begin() + static_cast<std::ptrdiff_t>(used));
    }

    void end() noexcept override { stream_.reset(); }

    fs::path node_;
    std::shared_ptr<SensorIo> io_;
    double per_unit_[3] = {1, 1, 1};
    double current_[3] = {0, 0, 0};  // an axis that did not change keeps its value
    std::unique_ptr<SensorDevice> stream_;
    std::vector<std::uint8_t> partial_;
};

}  // namespace

bool is_evdev_accelerometer(const fs::path& node, SensorIo& io) {
    try {
        const auto device = io.open_device(node);
        if (!device->has_input_property(INPUT_PROP_ACCELEROMETER)) {
            return false;
        }
        for (const unsigned axis : kAxes) {
            if (!device->abs_axis(axis)) {
                return false;
            }
        }
        return true;
    } catch (const std::runtime_error&) {
        return false;  // not ours to read (permissions), or gone
    }
}

std::unique_ptr<Accelerometer> open_evdev_accelerometer(const fs::path& node,
                                                        std::shared_ptr<SensorIo> io) {
    return std::make_unique<EvdevAccelerometer>(node, std::move(io));
}

}  // namespace vibscore::sensors
