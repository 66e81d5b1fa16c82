#include "daemon/drivers/sim_accelerometer.hpp"

#include <cmath>
#include <utility>

#include "common/monotonic_clock.hpp"
#include "common/number_text.hpp"

namespace vibscore::drivers {

SimAccelerometer::SimAccelerometer(const actuator::Declaration& truth,
                                   const actuator::SensorOptions& options)
    : truth_(truth), options_(options) {
    actuator::VibrationSensor check(truth_, options_);  // refuses what the model cannot take
}

void SimAccelerometer::command(std::int64_t t_ns, const actuator::Drive& drive) {
    const std::lock_guard lock(mutex_);
    drive_ = drive;
    if (recording_) {
        recording_->command(static_cast<double>(t_ns) * 1e-9, drive);
    }
}

std::string SimAccelerometer::describe() const {
    return "the sim's accelerometer (" + number_text(options_.rate_hz) + " Hz, noise " +
           number_text(options_.noise_rms) + " m/s\u00b2 RMS, true actuator " +
           actuator::describe(truth_) + ")";
}

void SimAccelerometer::start() {
    const double now_s = static_cast<double>(monotonic_now_ns()) * 1e-9;
    const std::lock_guard lock(mutex_);
    auto options = options_;
    options.first_sample_s = now_s;
    options.seed = options_.seed + recordings_++;
    recording_.emplace(truth_, options);
    recording_->command(now_s, drive_);
}

std::vector<sensors::Reading> SimAccelerometer::stop() {
    const double now_s = static_cast<double>(monotonic_now_ns()) * 1e-9;
    std::optional<actuator::VibrationSensor> recorded;
    {
        const std::lock_guard lock(mutex_);
        recorded.swap(recording_);
    }
    std::vector<sensors::Reading> readings;
    if (!recorded) {
        return readings;
    }
    // The model integrates here, on the caller's thread, outside the lock: the playback thread's
    // drives never wait for it.
    for (const auto& sample : recorded->sample_until(now_s)) {
        readings.push_back({static_cast<std::int64_t>(std::llround(sample.t_s * 1e9)), sample.x,
                            sample.y, sample.z});
    }
    return readings;
}

}  // namespace vibscore::drivers
