#include "tests/hil/uleds_led.hpp"

#include <fcntl.h>
#include <linux/uleds.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

namespace {
const std::filesystem::path kUleds = "/dev/uleds";
}  // namespace

UledsLed::UledsLed(const std::string& name, int max_brightness)
    : uleds_(::open(kUleds.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC)),
      sysfs_dir_(std::filesystem::path("/sys/class/leds") / name) {
    if (uleds_.get() < 0) {
        throw_errno("cannot open", kUleds);
    }
    if (name.empty() || name.size() >= LED_MAX_NAME_SIZE) {
        throw std::invalid_argument("uleds LED name \"" + name + "\" must have 1 to " +
                                    std::to_string(LED_MAX_NAME_SIZE - 1) + " characters");
    }
    if (std::filesystem::exists(sysfs_dir_)) {
        // The LED core would rename ours to NAME_1: the test would watch the wrong LED.
        throw std::runtime_error(sysfs_dir_.string() + " already exists");
    }
    uleds_user_dev device{};
    std::strncpy(device.name, name.c_str(), LED_MAX_NAME_SIZE - 1);
    device.max_brightness = max_brightness;
    if (::write(uleds_.get(), &device, sizeof device) != sizeof device) {
        throw_errno("cannot register LED \"" + name + "\" with", kUleds);
    }
    wait_for_path(sysfs_dir_);
    // uleds reports the initial brightness once after registering: not a change.
    int initial = 0;
    if (::read(uleds_.get(), &initial, sizeof initial) != sizeof initial) {
        throw_errno("cannot read the initial brightness from", kUleds);
    }
    thread_ = std::make_unique<FdServiceThread>(uleds_.get(), [this] { service(); });
}

UledsLed::~UledsLed() {
    thread_.reset();
}

void UledsLed::service() {
    int brightness = 0;
    for (;;) {
        const auto got = ::read(uleds_.get(), &brightness, sizeof brightness);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) {
            return;
        }
        if (got != sizeof brightness) {
            throw_errno("cannot read the brightness from", kUleds);
        }
        std::lock_guard lock(mutex_);
        changes_.push_back({std::chrono::steady_clock::now(), brightness});
        changed_.notify_all();
    }
}

std::vector<BrightnessChange> UledsLed::changes() const {
    std::lock_guard lock(mutex_);
    return changes_;
}

void UledsLed::clear_changes() {
    std::lock_guard lock(mutex_);
    changes_.clear();
}

bool UledsLed::wait_for(const std::function<bool(const BrightnessChange&)>& match,
                        std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {
        for (const auto& change : changes_) {
            if (match(change)) {
                return true;
            }
        }
        return false;
    });
}

}  // namespace vibscore::hil
