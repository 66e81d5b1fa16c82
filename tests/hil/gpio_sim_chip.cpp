#include "tests/hil/gpio_sim_chip.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <system_error>

#include "common/unique_fd.hpp"
#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

namespace {

const std::filesystem::path kConfigRoot = "/sys/kernel/config/gpio-sim";

std::string unique_chip_name() {
    static std::atomic<unsigned> counter{0};
    return "vibscore-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void make_directory(const std::filesystem::path& directory) {
    std::error_code error;
    if (!std::filesystem::create_directory(directory, error)) {
        throw std::system_error(error, "cannot create " + directory.string());
    }
}

}  // namespace

GpioSimChip::GpioSimChip(GpioSimOptions options) : lines_(options.lines) {
    if (!std::filesystem::is_directory(kConfigRoot)) {
        throw std::runtime_error(kConfigRoot.string() +
                                 " is missing: gpio-sim is not loaded or configfs not mounted");
    }
    config_ = kConfigRoot / unique_chip_name();
    make_directory(config_);
    const auto bank = config_ / "bank0";
    make_directory(bank);
    write_attribute(bank / "num_lines", std::to_string(options.lines));
    if (!options.label.empty()) {
        write_attribute(bank / "label", options.label);
    }
    for (std::size_t line = 0; line < options.line_names.size(); ++line) {
        const auto directory = bank / ("line" + std::to_string(line));
        make_directory(directory);
        write_attribute(directory / "name", options.line_names[line]);
    }
    write_attribute(config_ / "live", "1");
    chip_name_ = read_attribute(bank / "chip_name");
    chip_path_ = std::filesystem::path("/dev") / chip_name_;
    sysfs_ = std::filesystem::path("/sys/devices/platform") / read_attribute(config_ / "dev_name") /
             chip_name_;
    wait_for_path(chip_path_);
}

GpioSimChip::~GpioSimChip() {
    // Teardown in reverse; errors are ignored: a failed test must not turn into an abort here.
    try {
        write_attribute(config_ / "live", "0");
    } catch (const std::exception&) {
    }
    std::error_code ignored;
    for (unsigned line = 0; line < lines_; ++line) {
        std::filesystem::remove(config_ / "bank0" / ("line" + std::to_string(line)), ignored);
    }
    std::filesystem::remove(config_ / "bank0", ignored);
    std::filesystem::remove(config_, ignored);
}

std::filesystem::path GpioSimChip::value_file(unsigned line) const {
    if (line >= lines_) {
        throw std::out_of_range("gpio-sim " + chip_name_ + " has no line " + std::to_string(line));
    }
    return sysfs_ / ("sim_gpio" + std::to_string(line)) / "value";
}

int GpioSimChip::value(unsigned line) const {
    return std::stoi(read_attribute(value_file(line)));
}

void GpioSimChip::set_pull(unsigned line, bool up) const {
    write_attribute(value_file(line).parent_path() / "pull", up ? "pull-up" : "pull-down");
}

}  // namespace vibscore::hil
