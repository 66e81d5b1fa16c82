#include "tests/hil/gpio_value_trace.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

namespace {

const std::filesystem::path kDebugGpio = "/sys/kernel/debug/gpio";

std::filesystem::path tracing_root() {
    for (const char* root : {"/sys/kernel/tracing", "/sys/kernel/debug/tracing"}) {
        if (std::filesystem::exists(std::filesystem::path(root) / "instances")) {
            return root;
        }
    }
    throw std::runtime_error("no tracefs at /sys/kernel/tracing or /sys/kernel/debug/tracing");
}

// The global number of the chip's line 0: debugfs says "gpiochipN: GPIOs FIRST-LAST, ...".
unsigned first_gpio(const std::string& chip_name) {
    std::istringstream text(read_attribute(kDebugGpio));
    const std::string prefix = chip_name + ": GPIOs ";
    for (std::string line; std::getline(text, line);) {
        if (line.rfind(prefix, 0) == 0) {
            return static_cast<unsigned>(std::stoul(line.substr(prefix.size())));
        }
    }
    throw std::runtime_error(chip_name + " is not in " + kDebugGpio.string());
}

std::string instance_name() {
    static std::atomic<unsigned> counter{0};
    return "vibscore-gpio-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

}  // namespace

GpioValueTrace::GpioValueTrace(const GpioSimChip& chip)
    : base_(first_gpio(chip.chip_name())), lines_(chip.lines()) {
    const auto instance = tracing_root() / "instances" / instance_name();
    std::error_code error;
    if (!std::filesystem::create_directory(instance, error)) {
        throw std::system_error(error, "cannot create the tracing instance " + instance.string());
    }
    instance_ = instance;
    try {
        const auto event = instance_ / "events" / "gpio" / "gpio_value";
        write_attribute(event / "filter", "gpio >= " + std::to_string(base_) + " && gpio < " +
                                              std::to_string(base_ + lines_));
        write_attribute(event / "enable", "1");
    } catch (...) {
        std::filesystem::remove(instance_, error);
        throw;
    }
}

GpioValueTrace::~GpioValueTrace() {
    std::error_code ignored;
    // An instance is removed with everything in it by rmdir alone.
    std::filesystem::remove(instance_, ignored);
}

std::vector<GpioValueSet> GpioValueTrace::sets() const {
    // "  prog-123  [000] .....  12.345678: gpio_value: 1020 set 1"
    std::istringstream text(read_attribute(instance_ / "trace"));
    std::vector<GpioValueSet> sets;
    for (std::string line; std::getline(text, line);) {
        const auto at = line.find("gpio_value: ");
        if (line.rfind('#', 0) == 0 || at == std::string::npos) {
            continue;
        }
        unsigned gpio = 0;
        char operation[4] = {};
        int value = 0;
        if (std::sscanf(line.c_str() + at, "gpio_value: %u %3s %d", &gpio, operation, &value) !=
            3) {
            throw std::runtime_error("unexpected trace line: " + line);
        }
        if (std::string(operation) == "set" && gpio >= base_ && gpio < base_ + lines_) {
            sets.push_back({gpio - base_, value});
        }
    }
    return sets;
}

}  // namespace vibscore::hil
