#pragma once

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "actuator/declaration.hpp"
#include "common/event_loop.hpp"
#include "common/usage.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/playback_cues.hpp"
#include "daemon/playback_limits.hpp"
#include "daemon/playback_positions.hpp"
#include "daemon/render/cue_stream.hpp"

namespace vibscore::daemon {

struct PlaybackRequest {
    std::string label;  // registry name, or "<inline>"
    // One pass of the score's cues, made as playback advances and adapted to the actuator.
    std::shared_ptr<const render::CueSource> cues;
    double duration_s = 0.0;  // one pass
    Usage usage = Usage::notification;
    int repeat = 0;  // 0 once, n more times, -1 until stopped
    double intensity = 1.0;
    uid_t owner = 0;     // the user who asked; may stop it
    std::string sender;  // bus connection; when it leaves, the playback ends
    // The longest it may play, counted from its start across every repeat; past it, it ends
    // with over_on_time_reason() ("limit-exceeded: ..."). nullopt: until it ends or is stopped.
    // The bus service sets it from [limits] by usage (PlaybackLimits).
    std::optional<double> max_on_time_s;
    // Drives of the backend's full scale as they are (-1..1), not strengths: the calibration's
    // probe (Calibrate), which must reach the actuator unshaped by the declared actuator's
    // compensation, the intensities or the rated drive. Still clamped to full scale and to the
    // backend's reverse capability, and held to its maximum on-time.
    bool probe = false;
};

// What the player reports; the bus service turns these into signals.
class PlayerListener {
  public:
    virtual ~PlayerListener() = default;
    virtual void playback_started(std::uint64_t id, const std::string& label) = 0;
    virtual void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) = 0;
    virtual void playback_finished(std::uint64_t id, const std::string& reason) = 0;
};

// Why a playback ended, as PlaybackFinished says (dbus/org.vibscore.Haptics1.xml): a caller's
// Stop, and the service stopping (SIGTERM), which no caller asked for.
inline constexpr const char* kStopped = "stopped";
inline constexpr const char* kServiceStopped = "service-stopped";

// A repeating playback whose caller leaves the bus plays on only if it ends by itself within
// this long; otherwise it ends with "client-vanished". A stranger's fire-and-forget
// `repeat 2147483647` would otherwise pin the actuator for years, refusing everyone's
// equally important one-shots with Busy (docs/daemon.md, Who may do what).
inline constexpr double kPlaysOnWithoutItsCaller_s = 30.0;

// The fastest a playback's position is reported (PlaybackPosition): each report is a bus
// broadcast, and a UI shows no more than a few dozen a second. Positions in between are
// coalesced: the latest is reported when the interval has passed, or when the playback ends.
// PositionBudget bounds them per connection and in total as well, across playbacks.
inline constexpr std::uint64_t kPositionReportInterval_us = 20'000;  // 50 a second

// A request lost arbitration against the playback in progress.
class PlayerBusy : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Plays one score at a time on the actuator, each cue at its absolute CLOCK_MONOTONIC deadline
// (start + cue time), so lateness never accumulates. Arbitration between overlapping requests
// follows their usage; see dbus/org.vibscore.Haptics1.xml (Play) and docs/daemon.md. The player
// itself has no threads: it runs on the loop it is given (the daemon gives it a thread of its
// own, PlaybackThread).
class Player {
  public:
    // Reports to `listener` (none: set_listener() later, e.g. by the bus service built after it).
    // Playback ids count up from `first_id` (never 0).
    Player(EventLoop& loop, drivers::Actuator& actuator, PlayerListener* listener = nullptr,
           std::uint64_t first_id = 1);
    Player(EventLoop& loop, drivers::Actuator& actuator, PlayerListener& listener)
        : Player(loop, actuator, &listener) {}
    ~Player();
    Player(const Player&) = delete;
    Player& operator=(const Player&) = delete;

    // Throws PlayerBusy when a request of this usage and repeat would be refused now: a more
    // important (or a repeating, equally important) playback plays. Play asks this before it
    // renders anything, so a refused request costs next to nothing.
    void check_admission(Usage usage, int repeat) const;

    // Starts at once: the first drive reaches the actuator before this returns.
    // Throws PlayerBusy as check_admission() does.
    std::uint64_t play(PlaybackRequest request);

    enum class StopResult { stopped, not_playing, not_found, not_permitted };
    // Stops playback `id` (0: whatever `caller` has playing). Privileged callers may stop any.
    // An id this player never gave out (another run's, say) is not_found.
    StopResult stop(std::uint64_t id, uid_t caller, bool privileged);

    // The caller's bus connection went away: a playback of its that repeats (until stopped, or
    // so many times that it would end more than kPlaysOnWithoutItsCaller_s from now) ends with
    // "client-vanished". A one-shot plays on: it yields to any equally important request, so
    // it pins nothing.
    void sender_vanished(const std::string& sender);

    // A privileged "stop everyone's playbacks" (vibscore stop --all, org.vibscore.manage):
    // ends whatever plays, whoever started it, with reason "stopped" and the actuator off, and
    // starts its owner's cool-down (check_cool_down()). Returns the ids it ended; none when
    // nothing played.
    std::vector<std::uint64_t> stop_every_playback();

    // Throws CoolingDown when `owner` may not start a playback of this usage and repeat yet:
    // a playback of theirs was cut off (maximum on-time, stop_every_playback()) less than
    // `cool_down_s` ago (CoolDowns).
    void check_cool_down(uid_t owner, Usage usage, int repeat, double cool_down_s) const;

    // Ends any playback with `reason` and switches the actuator off (shutdown, driver switch).
    void stop_all(const std::string& reason);

    // Uses another actuator from now on; the current one is switched off first.
    void replace_actuator(drivers::Actuator& actuator);

    // The actuator [actuator] declares, from the next play() on: strength 1 is its rated drive,
    // and with compensation the cues are shaped to its physics (render::DrivePlanner). nullopt:
    // strengths are sent as written, as before there was a declaration.
    void set_actuator(std::optional<actuator::Declaration> declaration);

    void set_master_intensity(double intensity);
    double master_intensity() const { return master_intensity_; }

    std::optional<std::uint64_t> current_id() const;

    // Who hears of playback events from now on; nullptr: nobody.
    void set_listener(PlayerListener* listener);

  private:
    struct Playback {
        std::uint64_t id = 0;
        PlaybackRequest request;
        PlaybackCues cues;
        std::uint64_t start_us = 0;          // when pass 0 began
        std::uint64_t pass = 0;              // of the next cue
        drivers::Capabilities capabilities;  // of the actuator when it started
        // The cues are drives of the backend's full scale already (a declared actuator).
        bool final_drives = false;
    };

    std::uint64_t due_us(const Playback& playback, const PassCue& cue) const;
    void run_due();
    bool execute(const render::Cue& cue);
    drivers::Drive drive_for(const render::Cue& cue) const;
    void prepare_next_drive();
    // For a backend whose kernel ends a drive by itself: how long from now the schedule keeps
    // the actuator on (at most its maximum on-time).
    double seconds_until_off();
    // Thermal protection: when the actuator, on without a break, reaches its maximum on-time.
    std::optional<std::uint64_t> on_time_deadline_us() const;
    void finish(std::string reason);
    // A position cue: reported now, or held until the report interval has passed.
    void report_position(std::size_t bar, std::size_t symbol);
    // Reports a held position once the interval has passed and the budget allows (`force`: as
    // the playback ends: now if the budget allows, else never).
    void report_held_position(bool force);
    // When a held position may next be reported.
    std::uint64_t next_report_us(std::uint64_t now_us) const;
    // Ends the playback with "device-error: ...": the actuator failed under it.
    void fail(const drivers::DeviceError& error);

    EventLoop::Timer timer_;
    drivers::Actuator* actuator_;
    PlayerListener* listener_;
    std::optional<Playback> current_;
    std::uint64_t first_id_;
    std::uint64_t next_id_;
    double master_intensity_ = 1.0;
    std::optional<actuator::Declaration> declared_;
    // Since when the actuator has been on without a break, and whether it is held off until
    // the score itself stops driving it (after exceeding its maximum on-time).
    std::optional<std::uint64_t> on_since_us_;
    bool held_off_ = false;
    // Position reports of the current playback: when the last went out, and the latest one
    // held back since (bar, symbol).
    std::optional<std::uint64_t> last_report_us_;
    std::optional<std::pair<std::size_t, std::size_t>> held_position_;
    // Whose playbacks were cut off, and when: the player ends them, so it keeps the record.
    CoolDowns cool_downs_;
    // PlaybackPosition's bounds per connection and in total, across playbacks.
    PositionBudget positions_;
};

}  // namespace vibscore::daemon
