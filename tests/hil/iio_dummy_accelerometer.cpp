#include "tests/hil/iio_dummy_accelerometer.hpp"

#include <chrono>
#include <stdexcept>
#include <system_error>

#include "tests/hil/kernel_files.hpp"
#include "tests/support/pace.hpp"

namespace vibscore::hil {

namespace fs = std::filesystem;

namespace {

const fs::path kIioDevices = "/sys/bus/iio/devices";
const fs::path kDummyConfig = "/sys/kernel/config/iio/devices/dummy";
// iio-trig-sysfs names a trigger added with id K "sysfstrigK"; one the other tests do not use.
constexpr int kTriggerId = 32;

// The folder under /sys/bus/iio/devices whose `name` is `name` and that starts with `prefix`.
fs::path find_by_name(const std::string& prefix, const std::string& name) {
    for (const auto& entry : fs::directory_iterator(kIioDevices)) {
        const auto file = entry.path().filename().string();
        if (file.starts_with(prefix) && fs::exists(entry.path() / "name") &&
            read_attribute(entry.path() / "name") == name) {
            return entry.path();
        }
    }
    throw std::runtime_error("no " + prefix + "* named " + name + " in " + kIioDevices.string());
}

}  // namespace

IioDummyAccelerometer::IioDummyAccelerometer(const std::string& name) {
    wait_for_path(kDummyConfig);  // industrialio-configfs and iio_dummy are loaded by /init
    config_ = kDummyConfig / name;
    if (!fs::create_directory(config_)) {
        throw std::runtime_error(config_.string() + " already exists: a dummy was left behind");
    }
    folder_ = find_by_name("iio:device", name);
    const std::string trigger_name = "sysfstrig" + std::to_string(kTriggerId);
    write_attribute(kIioDevices / "iio_sysfs_trigger" / "add_trigger", std::to_string(kTriggerId));
    trigger_ = find_by_name("trigger", trigger_name);
    write_attribute(folder_ / "trigger" / "current_trigger", trigger_name);
}

IioDummyAccelerometer::~IioDummyAccelerometer() {
    stop_firing();
    try {
        // A name no trigger has detaches the trigger, then the device and the trigger go.
        write_attribute(folder_ / "trigger" / "current_trigger", "\n");
        fs::remove(config_);
        write_attribute(kIioDevices / "iio_sysfs_trigger" / "remove_trigger",
                        std::to_string(kTriggerId));
    } catch (const std::exception&) {
        // The guest is thrown away after the run; a failed test already said what went wrong.
    }
}

fs::path IioDummyAccelerometer::device() const {
    return fs::path("/dev") / folder_.filename();
}

void IioDummyAccelerometer::start_firing(std::chrono::microseconds period) {
    firing_ = true;
    firer_ = std::thread([this, period] {
        auto next = std::chrono::steady_clock::now();
        try {
            while (firing_) {
                write_attribute(trigger_ / "trigger_now", "1");
                ++fired_;
                next += period;
                // The device's sample rate: a period kept, not a wait for anything.
                vibscore::testing::pace_until(next);
            }
        } catch (const std::exception&) {
            // The trigger refused: the test sees fewer scans than fired and says so.
        }
    });
}

unsigned IioDummyAccelerometer::stop_firing() {
    firing_ = false;
    if (firer_.joinable()) {
        firer_.join();
    }
    return fired_;
}

}  // namespace vibscore::hil
