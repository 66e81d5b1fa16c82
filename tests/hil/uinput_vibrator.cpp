#include "tests/hil/uinput_vibrator.hpp"

#include <linux/uinput.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "tests/hil/kernel_files.hpp"
#include "tests/hil/uinput_device.hpp"

namespace vibscore::hil {

namespace {

std::chrono::steady_clock::time_point kernel_time(const input_event& event) {
    return std::chrono::steady_clock::time_point(std::chrono::seconds(event.input_event_sec) +
                                                 std::chrono::microseconds(event.input_event_usec));
}

const char* waveform_name(int waveform) {
    switch (waveform) {
        case FF_SQUARE:
            return "square";
        case FF_TRIANGLE:
            return "triangle";
        case FF_SINE:
            return "sine";
        case FF_SAW_UP:
            return "saw-up";
        case FF_SAW_DOWN:
            return "saw-down";
        case FF_CUSTOM:
            return "custom";
        default:
            return "?";
    }
}

void describe_effect(std::ostream& out, const ff_effect& effect) {
    out << " replay=" << effect.replay.length << "ms+" << effect.replay.delay << "ms";
    if (effect.type == FF_PERIODIC) {
        const auto& periodic = effect.u.periodic;
        out << " periodic " << waveform_name(periodic.waveform) << " period=" << periodic.period
            << "ms magnitude=" << periodic.magnitude << " offset=" << periodic.offset
            << " envelope=" << periodic.envelope.attack_length << "ms@"
            << periodic.envelope.attack_level << "/" << periodic.envelope.fade_length << "ms@"
            << periodic.envelope.fade_level;
    } else if (effect.type == FF_RUMBLE) {
        out << " rumble strong=" << effect.u.rumble.strong_magnitude
            << " weak=" << effect.u.rumble.weak_magnitude;
    } else if (effect.type == FF_CONSTANT) {
        out << " constant level=" << effect.u.constant.level;
    } else {
        out << " type=" << effect.type;
    }
}

}  // namespace

std::ostream& operator<<(std::ostream& out, FfEvent::Kind kind) {
    switch (kind) {
        case FfEvent::Kind::Created:
            return out << "created";
        case FfEvent::Kind::Upload:
            return out << "upload";
        case FfEvent::Kind::Erase:
            return out << "erase";
        case FfEvent::Kind::Play:
            return out << "play";
        case FfEvent::Kind::Gain:
            return out << "gain";
        case FfEvent::Kind::Autocenter:
            return out << "autocenter";
        case FfEvent::Kind::Destroyed:
            return out << "destroyed";
    }
    return out << "?";
}

std::ostream& operator<<(std::ostream& out, const FfEvent& event) {
    const auto ns = event.time.time_since_epoch().count();
    out << (ns / 1000000000) << "." << (ns / 1000 % 1000000) << " " << event.kind;
    switch (event.kind) {
        case FfEvent::Kind::Upload:
            out << " id=" << event.effect_id << " answer=" << event.value;
            describe_effect(out, event.effect);
            break;
        case FfEvent::Kind::Erase:
            out << " id=" << event.effect_id;
            break;
        case FfEvent::Kind::Play:
            out << " id=" << event.effect_id << " value=" << event.value;
            break;
        case FfEvent::Kind::Gain:
        case FfEvent::Kind::Autocenter:
            out << " value=" << event.value;
            break;
        default:
            break;
    }
    return out;
}

UinputVibratorOptions UinputVibratorOptions::phone_vibrator() {
    UinputVibratorOptions options;
    options.name = "pm8xxx-vibrator";
    options.phys = "pm8xxx-vibrator/input0";
    options.id = {BUS_HOST, 0, 0, 0};
    options.ff_bits = {FF_RUMBLE, FF_PERIODIC, FF_SQUARE,   FF_TRIANGLE,
                       FF_SINE,   FF_SAW_UP,   FF_SAW_DOWN, FF_GAIN};
    options.mark_as_vibra = true;
    return options;
}

UinputVibrator::UinputVibrator(UinputVibratorOptions options) : options_(std::move(options)) {
    create();
}

UinputVibrator::~UinputVibrator() {
    if (!exists()) {
        return;
    }
    try {
        destroy();
    } catch (const std::exception& error) {
        // Closing the uinput fd below removes the device anyway.
        std::fprintf(stderr, "UinputVibrator: %s\n", error.what());
    }
}

void UinputVibrator::create() {
    UniqueFd fd = open_uinput();
    uinput_ioctl(fd.get(), UI_SET_EVBIT, "UI_SET_EVBIT EV_FF", EV_FF);
    for (const int bit : options_.ff_bits) {
        uinput_ioctl(fd.get(), UI_SET_FFBIT, "UI_SET_FFBIT", static_cast<unsigned long>(bit));
    }
    if (!options_.phys.empty()) {
        uinput_ioctl(fd.get(), UI_SET_PHYS, "UI_SET_PHYS",
                     reinterpret_cast<unsigned long>(options_.phys.c_str()));
    }
    uinput_setup setup{};
    setup.id = options_.id;
    std::strncpy(setup.name, options_.name.c_str(), UINPUT_MAX_NAME_SIZE - 1);
    setup.ff_effects_max = options_.effects_max;
    auto nodes = create_uinput_device(fd.get(), setup);
    input_name_ = std::move(nodes.input_name);
    event_node_ = std::move(nodes.event_node);
    if (options_.mark_as_vibra) {
        write_udev_entry();
    }

    uinput_ = std::move(fd);
    record({FfEvent::Kind::Created, std::chrono::steady_clock::now()});
    thread_ = std::make_unique<FdServiceThread>(uinput_.get(), [this] { service(); });
}

void UinputVibrator::write_udev_entry() {
    struct stat node {};
    if (::stat(event_node_.c_str(), &node) != 0) {
        throw_errno("cannot stat", event_node_);
    }
    std::filesystem::create_directories(options_.udev_data);
    udev_entry_ = options_.udev_data / ("c" + std::to_string(major(node.st_rdev)) + ":" +
                                        std::to_string(minor(node.st_rdev)));
    std::ofstream entry(udev_entry_);
    entry << "E:FEEDBACKD_TYPE=vibra\n";
    if (!entry.flush()) {
        throw std::runtime_error("cannot write " + udev_entry_.string());
    }
}

void UinputVibrator::destroy() {
    // Requests the kernel still waits for are failed with ENODEV by UI_DEV_DESTROY itself.
    thread_.reset();
    uinput_ioctl(uinput_.get(), UI_DEV_DESTROY, "UI_DEV_DESTROY", 0);
    uinput_.close();
    if (!udev_entry_.empty()) {
        std::filesystem::remove(udev_entry_);
        udev_entry_.clear();
    }
    std::lock_guard lock(mutex_);
    effects_.clear();
    playing_.clear();
    timeline_.push_back({FfEvent::Kind::Destroyed, std::chrono::steady_clock::now()});
    changed_.notify_all();
}

void UinputVibrator::recreate() {
    if (exists()) {
        destroy();
    }
    create();
}

void UinputVibrator::answer_uploads_with(int error) {
    std::lock_guard lock(mutex_);
    upload_error_ = error;
}

void UinputVibrator::service() {
    input_event event{};
    for (;;) {
        const auto got = ::read(uinput_.get(), &event, sizeof event);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) {
            return;
        }
        if (got != sizeof event) {
            throw_errno("cannot read an event from", kUinput);
        }
        if (event.type == EV_UINPUT && event.code == UI_FF_UPLOAD) {
            answer_upload(event);
        } else if (event.type == EV_UINPUT && event.code == UI_FF_ERASE) {
            answer_erase(event);
        } else if (event.type == EV_FF && event.code == FF_GAIN) {
            record({FfEvent::Kind::Gain, kernel_time(event), -1, event.value});
        } else if (event.type == EV_FF && event.code == FF_AUTOCENTER) {
            record({FfEvent::Kind::Autocenter, kernel_time(event), -1, event.value});
        } else if (event.type == EV_FF) {
            record({FfEvent::Kind::Play, kernel_time(event), event.code, event.value});
        }
    }
}

void UinputVibrator::answer_upload(const input_event& request) {
    uinput_ff_upload upload{};
    upload.request_id = static_cast<__u32>(request.value);
    uinput_ioctl(uinput_.get(), UI_BEGIN_FF_UPLOAD, "UI_BEGIN_FF_UPLOAD",
                 reinterpret_cast<unsigned long>(&upload));
    {
        std::lock_guard lock(mutex_);
        upload.retval = -upload_error_;
    }
    FfEvent event{FfEvent::Kind::Upload, kernel_time(request), upload.effect.id, upload.retval};
    event.effect = upload.effect;
    event.old = upload.old;
    // Recorded before answering: the client may act on the answer at once.
    record(event);
    uinput_ioctl(uinput_.get(), UI_END_FF_UPLOAD, "UI_END_FF_UPLOAD",
                 reinterpret_cast<unsigned long>(&upload));
}

void UinputVibrator::answer_erase(const input_event& request) {
    uinput_ff_erase erase{};
    erase.request_id = static_cast<__u32>(request.value);
    uinput_ioctl(uinput_.get(), UI_BEGIN_FF_ERASE, "UI_BEGIN_FF_ERASE",
                 reinterpret_cast<unsigned long>(&erase));
    erase.retval = 0;
    record({FfEvent::Kind::Erase, kernel_time(request), static_cast<int>(erase.effect_id), 0});
    uinput_ioctl(uinput_.get(), UI_END_FF_ERASE, "UI_END_FF_ERASE",
                 reinterpret_cast<unsigned long>(&erase));
}

void UinputVibrator::record(FfEvent event) {
    std::lock_guard lock(mutex_);
    switch (event.kind) {
        case FfEvent::Kind::Upload:
            if (event.value == 0) {
                effects_[event.effect_id] = event.effect;
            }
            break;
        case FfEvent::Kind::Erase:
            effects_.erase(event.effect_id);
            playing_.erase(event.effect_id);
            break;
        case FfEvent::Kind::Play:
            if (event.value != 0) {
                playing_.insert(event.effect_id);
            } else {
                playing_.erase(event.effect_id);
            }
            break;
        default:
            break;
    }
    timeline_.push_back(event);
    changed_.notify_all();
}

std::vector<FfEvent> UinputVibrator::timeline() const {
    std::lock_guard lock(mutex_);
    return timeline_;
}

void UinputVibrator::clear_timeline() {
    std::lock_guard lock(mutex_);
    timeline_.clear();
}

bool UinputVibrator::wait_for(const std::function<bool(const FfEvent&)>& match,
                              std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {
        for (const auto& event : timeline_) {
            if (match(event)) {
                return true;
            }
        }
        return false;
    });
}

std::map<int, ff_effect> UinputVibrator::effects() const {
    std::lock_guard lock(mutex_);
    return effects_;
}

std::set<int> UinputVibrator::playing() const {
    std::lock_guard lock(mutex_);
    return playing_;
}

}  // namespace vibscore::hil
