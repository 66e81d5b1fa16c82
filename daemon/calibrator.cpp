#include "daemon/calibrator.hpp"

#include <chrono>
#include <map>
#include <utility>

#include "common/log.hpp"
#include "common/monotonic_clock.hpp"
#include "daemon/calibration_state.hpp"
#include "daemon/render/cue_stream.hpp"
#include "daemon/sensors/open_accelerometer.hpp"

namespace vibscore::daemon {

namespace cal = actuator::calibration;

namespace {

// After the probe's last drive the recording goes on this long: readings the sensor took while
// the probe ended may reach the reader a little later (an IIO buffer's watermark, an evdev
// SYN_REPORT).
constexpr auto kRecordingTail = std::chrono::milliseconds(100);
// How long the probe's end is waited for beyond its length before the run gives up: a player
// that never says it ended is a bug, and the caller must hear of it within D-Bus's patience.
constexpr auto kEndPatience = std::chrono::seconds(10);

constexpr const char* kProbeLabel = "<calibration>";

// The plan as a playback: every row a drive of the backend's full scale, as it is.
std::shared_ptr<const render::CueSource> probe_cues(const cal::Plan& plan) {
    std::vector<render::Cue> cues;
    for (const auto& row : plan.rows) {
        cues.push_back(render::drive_at(row.t_s, row.amplitude, row.frequency_hz));
    }
    return std::make_shared<render::CueList>(std::move(cues));
}

}  // namespace

struct Calibrator::Run {
    bool apply = false;
    uid_t owner = 0;
    std::string sender;
    Done done;
    cal::Plan plan;
    std::optional<actuator::Declaration> declared;
    std::string declared_source;
    std::shared_ptr<sensors::Accelerometer> sensor;
    std::string sensor_name;

    // Shared by the bus thread and the run's thread.
    std::mutex mutex;
    std::condition_variable changed;
    bool probe_started = false;  // (or failed to start)
    std::optional<std::uint64_t> playback_id;
    std::int64_t t0_ns = 0;                         // the probe's first drive
    std::map<std::uint64_t, std::string> finished;  // playbacks that ended since it began
    std::optional<std::string> ended;               // why the probe's playback ended
    std::optional<std::uint64_t> intruder;          // another playback that started while recording
    bool abandoned = false;                         // the calibrator is going away

    // The run's thread's, read on the bus thread once it is done.
    std::optional<CalibrationOutcome> outcome;
    std::exception_ptr error;
};

Calibrator::Calibrator(DaemonConfig& config, PlaybackThread& playback, ActuatorHost& host)
    : config_(config), playback_(playback), host_(host) {}

Calibrator::~Calibrator() {
    if (running_) {
        const std::lock_guard lock(running_->mutex);
        running_->abandoned = true;
        running_->changed.notify_all();
    }
    if (worker_.joinable()) {
        worker_.join();
    }
}

std::filesystem::path Calibrator::state_file() const {
    return config_.store / kCalibrationStateFile;
}

std::shared_ptr<sensors::Accelerometer> Calibrator::accelerometer() {
    const auto& section = config_.settings_of(kCalibrationSection);
    const auto setting = section.find("accelerometer");
    const std::string choice = setting == section.end() ? "auto" : setting->second;
    auto own = playback_.call([&host = host_](Player&) { return host.actuator().accelerometer(); });
    return sensors::open_accelerometer(choice, std::move(own));
}

void Calibrator::start(bool apply, uid_t owner, const std::string& sender, Done done) {
    if (running_) {
        throw PlayerBusy("a calibration is already running; wait for its answer");
    }
    if (!config_.actuator) {
        throw std::invalid_argument(
            "Calibrate measures the actuator [actuator] declares, and vibscored.conf declares "
            "none: add [actuator] with kind = erm or lra (docs/drivers.md, \"Declaring the "
            "actuator\"), then calibrate to measure its numbers");
    }
    auto sensor = accelerometer();
    if (!sensor) {
        throw CalibrationRefused(
            CalibrationRefused::Why::no_accelerometer,
            "no accelerometer to measure with: none was found (auto looks for an IIO device with "
            "in_accel channels under /sys/bus/iio/devices, then an evdev accelerometer); set "
            "[calibration] accelerometer = PATH in vibscored.conf (an IIO device such as "
            "/sys/bus/iio/devices/iio:device0, or /dev/input/eventN), or with driver = sim give "
            "[sim] accelerometer-rate-hz above 0");
    }
    // Refused before anything is recorded when something more important plays.
    playback_.call([](Player& player) { player.check_admission(Usage::hardware_feedback, 0); });
    auto run = std::make_shared<Run>();
    run->apply = apply;
    run->owner = owner;
    run->sender = sender;
    run->done = std::move(done);
    run->declared = config_.actuator;
    run->declared_source = config_.actuator_source;
    run->plan = cal::make_plan(config_.actuator->kind, config_.actuator);
    run->sensor = std::move(sensor);
    run->sensor_name = run->sensor->describe();
    if (worker_.joinable()) {
        worker_.join();  // the last run's thread, done by now
    }
    running_ = run;
    log::info("calibration: probing the actuator (" + actuator::describe(*config_.actuator) + ", " +
              std::to_string(run->plan.duration_s()) + " s) with " + run->sensor_name);
    worker_ = std::thread([this, run] { record(run); });
}

void Calibrator::playback_started(std::uint64_t id) {
    if (!running_) {
        return;
    }
    const std::lock_guard lock(running_->mutex);
    if (running_->playback_id && *running_->playback_id != id && !running_->intruder) {
        running_->intruder = id;  // it vibrates over the probe's end: the recording is spoilt
    }
}

void Calibrator::playback_finished(std::uint64_t id, const std::string& reason) {
    if (!running_) {
        return;
    }
    const std::lock_guard lock(running_->mutex);
    running_->finished[id] = reason;
    if (running_->playback_id == id) {
        running_->ended = reason;
        running_->changed.notify_all();
    }
}

// The run's thread: record while the bus thread starts the probe, until the probe ends.
void Calibrator::record(const std::shared_ptr<Run>& run) {
    const auto to_bus = [this, run] {
        playback_.to_bus([this, run] {
            if (!run->abandoned) {
                finish(run);
            }
        });
    };
    try {
        run->sensor->start();
    } catch (...) {
        run->error = std::current_exception();
        to_bus();
        return;
    }
    // The probe starts on the bus thread (the only one that may call the playback thread), once
    // the accelerometer records.
    playback_.to_bus([this, run] {
        if (run->abandoned) {
            return;
        }
        PlaybackRequest request;
        request.label = kProbeLabel;
        request.cues = probe_cues(run->plan);
        request.duration_s = run->plan.duration_s();
        request.usage = Usage::hardware_feedback;
        request.owner = run->owner;
        request.sender = run->sender;
        request.probe = true;
        std::exception_ptr failed;
        std::optional<std::pair<std::uint64_t, std::int64_t>> started;
        try {
            started = playback_.call([request = std::move(request)](Player& player) mutable {
                const std::int64_t t0 = monotonic_now_ns();
                return std::pair(player.play(std::move(request)), t0);
            });
        } catch (...) {
            failed = std::current_exception();
        }
        const std::lock_guard lock(run->mutex);
        run->probe_started = true;
        if (started) {
            run->playback_id = started->first;
            run->t0_ns = started->second;
            // It may have ended already (a failing first drive) before its id was known here.
            if (const auto ended = run->finished.find(started->first);
                ended != run->finished.end()) {
                run->ended = ended->second;
            }
        } else {
            run->error = failed;
        }
        run->changed.notify_all();
    });
    std::unique_lock lock(run->mutex);
    const auto patience =
        std::chrono::milliseconds(static_cast<long>(run->plan.duration_s() * 1000.0)) +
        kEndPatience;
    const bool ended = run->changed.wait_for(lock, patience, [&] {
        return run->abandoned || run->error || (run->probe_started && run->ended);
    });
    if (!run->abandoned && !run->error && ended && run->ended == "completed") {
        // The player is done with the probe's last drive, but the plan goes on after it (the
        // last coast, the last free ring-down) until its end; and the readings the sensor took
        // by then are still on their way.
        const auto plan_end = std::chrono::nanoseconds(
            run->t0_ns + static_cast<std::int64_t>(run->plan.duration_s() * 1e9) -
            monotonic_now_ns());
        run->changed.wait_for(lock,
                              std::max(plan_end, std::chrono::nanoseconds(0)) + kRecordingTail,
                              [&] { return run->abandoned; });
    }
    if (run->intruder && run->ended == "completed") {
        run->ended = "playback " + std::to_string(*run->intruder) + " started";
    }
    const auto reason = run->ended;
    const std::int64_t t0_ns = run->t0_ns;
    const bool gave_up = run->abandoned || run->error;
    lock.unlock();
    std::vector<sensors::Reading> readings;
    try {
        readings = run->sensor->stop();
    } catch (...) {
        if (!gave_up) {
            const std::lock_guard failed(run->mutex);
            run->error = std::current_exception();
            to_bus();
            return;
        }
    }
    if (gave_up) {
        to_bus();
        return;
    }
    try {
        if (!reason) {
            throw std::runtime_error("the calibration's probe did not end within " +
                                     std::to_string(patience.count()) + " ms of its start");
        }
        if (*reason != "completed") {
            throw CalibrationRefused(
                CalibrationRefused::Why::interrupted,
                "the probe was cut short (" + *reason +
                    "): another playback took over (a ringtone or an alarm, say) or it was "
                    "stopped; nothing was measured and nothing changed. Calibrate again when the "
                    "device is quiet");
        }
        CalibrationOutcome outcome;
        outcome.plan = run->plan;
        outcome.declared = run->declared;
        outcome.declared_source = run->declared_source;
        outcome.accelerometer = run->sensor_name;
        outcome.samples.reserve(readings.size());
        for (const auto& reading : readings) {
            outcome.samples.push_back({static_cast<double>(reading.t_ns - t0_ns) * 1e-9, reading.x,
                                       reading.y, reading.z});
        }
        outcome.estimate = cal::estimate(outcome.plan, outcome.samples, outcome.declared);
        run->outcome = std::move(outcome);
    } catch (...) {
        run->error = std::current_exception();
    }
    to_bus();
}

// Back on the bus thread: apply when asked and trusted, and answer.
void Calibrator::finish(const std::shared_ptr<Run>& run) {
    if (running_ == run) {
        running_.reset();
    }
    if (run->error) {
        run->done(std::nullopt, run->error);
        return;
    }
    auto& outcome = *run->outcome;
    const auto& estimate = outcome.estimate;
    log::info(std::string("calibration: ") + (estimate.trusted ? "trusted" : "not trusted") +
              ", residual " + std::to_string(estimate.residual) + ", snr " +
              std::to_string(estimate.snr_db) + " dB, " + std::to_string(outcome.samples.size()) +
              " readings");
    try {
        if (run->apply) {
            if (!estimate.trusted) {
                std::string why;
                for (const auto& problem : estimate.problems) {
                    why += " " + problem;
                }
                throw CalibrationRefused(
                    CalibrationRefused::Why::untrusted,
                    "the estimate is not trusted, so nothing was applied:" +
                        (why.empty() ? std::string(" (no reason given)") : why) + "\n" +
                        cal::declaration_lines(estimate));
            }
            apply_measured(outcome);
        }
        outcome.source = config_.actuator_source;
    } catch (...) {
        run->done(std::nullopt, std::current_exception());
        return;
    }
    run->done(std::move(outcome), nullptr);
}

void Calibrator::apply_measured(CalibrationOutcome& outcome) {
    const auto measured = measured_from(outcome.estimate, iso_utc_now());
    // Kept first: numbers in use that a restart would lose are worse than none applied.
    save_measured(state_file(), measured);
    playback_.call([&config = config_, measured](Player& player) {
        if (!config.actuator || config.actuator->kind != measured.kind) {
            return;  // a reload changed the declaration meanwhile; the next start sorts it out
        }
        config.actuator = with_measured(*config.actuator, measured);
        if (config.device_clefs.fit_to) {
            config.device_clefs.fit_to = config.actuator;
        }
        config.actuator_source = measured_source(measured);
        player.set_actuator(config.actuator);
    });
    outcome.applied = true;
    log::info("calibration: applied, kept in " + state_file().string() + ": " +
              actuator::describe(*config_.actuator));
}

}  // namespace vibscore::daemon
