#include "tests/hil/virtual_vibra_node.hpp"

#include <fcntl.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "common/unique_fd.hpp"
#include "daemon/drivers/evdev_discovery.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {

namespace fs = std::filesystem;

namespace {

std::string phys_of(const fs::path& node) {
    UniqueFd fd(::open(node.c_str(), O_RDONLY | O_CLOEXEC));
    char phys[128] = {};
    if (fd.get() < 0 || ::ioctl(fd.get(), EVIOCGPHYS(sizeof phys - 1), phys) < 0) {
        return {};
    }
    return phys;
}

}  // namespace

std::optional<fs::path> find_virtual_vibra(std::chrono::milliseconds timeout) {
    std::optional<fs::path> found;
    vibscore::testing::wait_until(
        [&] {
            std::error_code error;
            for (const auto& entry : fs::directory_iterator("/dev/input", error)) {
                if (entry.path().filename().string().starts_with("event") &&
                    phys_of(entry.path()) == drivers::kVirtualVibraPhys) {
                    found = entry.path();
                    return true;
                }
            }
            return false;
        },
        timeout, std::chrono::milliseconds(20));
    return found;
}

FeedbackdVibraMark::FeedbackdVibraMark(const fs::path& event_node, const fs::path& udev_data) {
    struct stat status {};
    if (::stat(event_node.c_str(), &status) != 0) {
        throw std::runtime_error("cannot stat " + event_node.string());
    }
    fs::create_directories(udev_data);
    entry_ = udev_data / ("c" + std::to_string(major(status.st_rdev)) + ":" +
                          std::to_string(minor(status.st_rdev)));
    std::ofstream(entry_) << "E:FEEDBACKD_TYPE=vibra\nE:ID_INPUT=1\n";
}

FeedbackdVibraMark::~FeedbackdVibraMark() {
    std::error_code ignored;
    fs::remove(entry_, ignored);
}

}  // namespace vibscore::hil
