#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "actuator/physics.hpp"
#include "actuator/vibration_sensor.hpp"
#include "daemon/sensors/accelerometer.hpp"

namespace vibscore::drivers {

// The sim backend's accelerometer: what a phone's accelerometer would record of the simulated
// actuator (actuator::VibrationSensor: the TRUE physics, which [sim] true-* keys may set apart
// from the declaration, with a real sensor's noise, quantisation, gravity and timestamp jitter).
// The sim actuator tells it every drive it applies (on the playback thread); a calibration
// records with it (on its own thread). It models only while it records: a recording starts
// from the actuator at rest with the drive in force, so hours of idle uptime cost nothing.
class SimAccelerometer final : public sensors::Accelerometer {
  public:
    // Throws std::invalid_argument for a truth or options the model refuses.
    SimAccelerometer(const actuator::Declaration& truth, const actuator::SensorOptions& options);

    // From `t_ns` (CLOCK_MONOTONIC) on, the actuator is driven with `drive`. Cheap: it queues.
    void command(std::int64_t t_ns, const actuator::Drive& drive);

    std::string describe() const override;
    void start() override;
    std::vector<sensors::Reading> stop() override;

  private:
    actuator::Declaration truth_;
    actuator::SensorOptions options_;
    std::mutex mutex_;
    actuator::Drive drive_{};  // in force now
    std::optional<actuator::VibrationSensor> recording_;
    std::uint64_t recordings_ = 0;  // each one's noise is its own
};

}  // namespace vibscore::drivers
