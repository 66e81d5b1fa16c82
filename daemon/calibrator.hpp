#pragma once

#include <sys/types.h>

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "actuator/calibration.hpp"
#include "daemon/actuator_host.hpp"
#include "daemon/config.hpp"
#include "daemon/playback_thread.hpp"
#include "daemon/sensors/accelerometer.hpp"

namespace vibscore::daemon {

// Calibrate's refusals that no other error names: no accelerometer to measure with, and an
// estimate too poor to apply (dbus/org.vibscore.Haptics1.xml).
class CalibrationRefused : public std::runtime_error {
  public:
    enum class Why { no_accelerometer, untrusted, interrupted };
    CalibrationRefused(Why why, const std::string& message)
        : std::runtime_error(message), why_(why) {}
    Why why() const { return why_; }

  private:
    Why why_;
};

// What one calibration found.
struct CalibrationOutcome {
    actuator::calibration::Plan plan;
    std::vector<actuator::calibration::Sample> samples;  // seconds from the probe's start
    actuator::calibration::Estimate estimate;
    std::optional<actuator::Declaration> declared;  // the numbers in use when it began
    std::string declared_source;                    // and where they came from
    std::string accelerometer;                      // what recorded it
    bool applied = false;
    std::string source;  // of the numbers in use now ("declared", "measured DATE")
};

// `vibscore calibrate` in the daemon (docs/daemon.md, "Calibration"): plays the calibration
// library's probe on the actuator as a playback of its own (usage hardware-feedback, drives as
// they are, never above full scale) while the accelerometer records, then estimates the
// actuator's numbers; with `apply` and a trusted estimate, makes them the numbers in use (kept in
// the store's state file). Lives on the bus thread; the recording and the estimate run on a
// thread of its own, so the bus never waits for them. One calibration at a time.
class Calibrator {
  public:
    using Done = std::function<void(std::optional<CalibrationOutcome>, std::exception_ptr)>;

    // `config` is the running configuration (its [calibration] section names the accelerometer;
    // an apply changes its actuator); all must outlive this.
    Calibrator(DaemonConfig& config, PlaybackThread& playback, ActuatorHost& host);
    ~Calibrator();
    Calibrator(const Calibrator&) = delete;
    Calibrator& operator=(const Calibrator&) = delete;

    // Starts a calibration for the caller (`owner`, `sender`, as a playback's). `done` runs on
    // the bus thread with the outcome, or with what went wrong: CalibrationRefused, PlayerBusy
    // (something more important plays), std::invalid_argument (nothing declared to measure),
    // std::runtime_error (the accelerometer failed). Throws those at once when known at once.
    void start(bool apply, uid_t owner, const std::string& sender, Done done);

    // The service's PlayerListener hears of every playback's start and end and tells this (bus
    // thread): the probe's end, or another playback over the probe's last coast or ring-down
    // (the player is done with the probe before the plan ends), spoiling the recording.
    void playback_started(std::uint64_t id);
    void playback_finished(std::uint64_t id, const std::string& reason);

    // The state file's path (the store's kCalibrationStateFile).
    std::filesystem::path state_file() const;

  private:
    struct Run;

    void record(const std::shared_ptr<Run>& run);
    void finish(const std::shared_ptr<Run>& run);
    void apply_measured(CalibrationOutcome& outcome);
    std::shared_ptr<sensors::Accelerometer> accelerometer();

    DaemonConfig& config_;
    PlaybackThread& playback_;
    ActuatorHost& host_;
    std::shared_ptr<Run> running_;  // bus thread only
    std::thread worker_;
};

}  // namespace vibscore::daemon
