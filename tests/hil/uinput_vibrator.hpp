#pragma once

#include <linux/input.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"
#include "tests/hil/fd_service_thread.hpp"

namespace vibscore::hil {

// One thing the kernel told a UinputVibrator, or a change of its own life.
struct FfEvent {
    enum class Kind { Created, Upload, Erase, Play, Gain, Autocenter, Destroyed };
    Kind kind = Kind::Created;
    // CLOCK_MONOTONIC: for requests and EV_FF events the kernel's own timestamp of the event
    // (microseconds), for Created/Destroyed when that happened.
    std::chrono::steady_clock::time_point time;
    int effect_id = -1;  // Upload (the id the kernel assigned), Erase, Play
    // Play: the repeat count, 0 = stop; Gain, Autocenter: 0..0xffff;
    // Upload, Erase: the answer given to the kernel (0 or -errno).
    int value = 0;
    ff_effect effect{};  // Upload: the effect as the client sent it
    ff_effect old{};     // Upload: the version it replaces, when an uploaded effect is updated
};

std::ostream& operator<<(std::ostream& out, const FfEvent& event);
std::ostream& operator<<(std::ostream& out, FfEvent::Kind kind);

struct UinputVibratorOptions {
    std::string name = "vibscore-hil-vibrator";
    std::string phys;  // empty: none
    input_id id{BUS_VIRTUAL, 0x1209, 0x0001, 1};
    // FF_PERIODIC needs a waveform bit (FF_SINE...) too, or the kernel refuses periodic uploads.
    std::vector<int> ff_bits{FF_PERIODIC, FF_SINE, FF_SQUARE, FF_RUMBLE, FF_GAIN};
    unsigned effects_max = 16;
    // Marks the device as feedbackd's udev rules mark a phone's vibra: a udev database entry
    // <udev_data>/c<major>:<minor> with E:FEEDBACKD_TYPE=vibra (the guest has no udev; /run
    // is a tmpfs there). Removed with the device.
    bool mark_as_vibra = false;
    std::filesystem::path udev_data = "/run/udev/data";

    // Looks like a phone's vibrator: Qualcomm's pm8xxx-vibrator on the host bus, only force
    // feedback (no keys), with the waveforms ff-memless offers on top of rumble, marked as vibra.
    static UinputVibratorOptions phone_vibrator();
};

// A force-feedback input device made with /dev/uinput, standing in for a vibrator driver. Its
// own thread answers the kernel's upload and erase requests (accepting them unless told to
// fail) and records everything in a timeline. A client reaches it through event_node(), the
// real evdev interface.
class UinputVibrator {
  public:
    explicit UinputVibrator(UinputVibratorOptions options = {});
    ~UinputVibrator();
    UinputVibrator(const UinputVibrator&) = delete;
    UinputVibrator& operator=(const UinputVibrator&) = delete;

    // /dev/input/eventN while the device exists.
    const std::filesystem::path& event_node() const { return event_node_; }
    // The input device's sysfs name (inputN), e.g. for /sys/class/input/inputN/name.
    const std::string& input_name() const { return input_name_; }
    // The udev database entry written for mark_as_vibra (empty path when not marked).
    const std::filesystem::path& udev_entry() const { return udev_entry_; }
    bool exists() const { return uinput_.get() >= 0; }

    // Removes the device, as if unplugged: clients' fds fail with ENODEV from then on.
    void destroy();
    // The same device again, with a new event node.
    void recreate();

    // The answer to upload requests from now on: 0 accepts, else the errno to fail with.
    void answer_uploads_with(int error);

    std::vector<FfEvent> timeline() const;
    void clear_timeline();
    // Waits until the timeline holds an event matching `match`; false after `timeout`.
    bool wait_for(const std::function<bool(const FfEvent&)>& match,
                  std::chrono::milliseconds timeout = std::chrono::seconds(5)) const;
    // Effects uploaded and not erased since, by id.
    std::map<int, ff_effect> effects() const;
    // Ids of the effects whose last Play was a start and that were not erased since.
    std::set<int> playing() const;

  private:
    void create();
    void write_udev_entry();
    void service();  // runs on the service thread
    void answer_upload(const input_event& request);
    void answer_erase(const input_event& request);
    void record(FfEvent event);

    const UinputVibratorOptions options_;
    UniqueFd uinput_;
    std::unique_ptr<FdServiceThread> thread_;
    std::filesystem::path event_node_;
    std::string input_name_;
    std::filesystem::path udev_entry_;

    mutable std::mutex mutex_;  // guards what follows
    mutable std::condition_variable changed_;
    std::vector<FfEvent> timeline_;
    std::map<int, ff_effect> effects_;
    std::set<int> playing_;
    int upload_error_ = 0;
};

}  // namespace vibscore::hil
