#include "tests/hil/pwm_sim_chip.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

namespace {

const std::filesystem::path kDebugfs = "/sys/kernel/debug/pwm-sim";

// The value of `key=` in a line of pwm-sim's text, or throws naming the line.
std::string field(const std::string& line, const std::string& key) {
    const auto start = line.find(" " + key + "=");
    if (start == std::string::npos) {
        throw std::runtime_error("pwm-sim line without " + key + ": " + line);
    }
    const auto value = start + key.size() + 2;
    return line.substr(value, line.find(' ', value) - value);
}

std::uint64_t number(const std::string& line, const std::string& key) {
    return std::stoull(field(line, key));
}

}  // namespace

std::ostream& operator<<(std::ostream& out, const PwmApplied& applied) {
    return out << "pwm" << applied.channel << " enabled=" << applied.enabled
               << " period=" << applied.period_ns << " duty_cycle=" << applied.duty_cycle_ns
               << (applied.inversed ? " inversed" : "");
}

PwmSimChip::PwmSimChip() {
    for (const auto& entry : std::filesystem::directory_iterator("/sys/class/pwm")) {
        // pwmchipN/device is the chip's parent: the platform device pwm-sim registered.
        std::error_code error;
        const auto device = std::filesystem::read_symlink(entry.path() / "device", error);
        if (!error && device.filename() == "pwm-sim") {
            sysfs_dir_ = entry.path();
        }
    }
    if (sysfs_dir_.empty()) {
        throw std::runtime_error("no /sys/class/pwm/pwmchipN of pwm-sim: is the module loaded?");
    }
    channels_ = static_cast<unsigned>(std::stoul(read_attribute(sysfs_dir_ / "npwm")));
    clear_log();
}

PwmSimChip::~PwmSimChip() {
    for (unsigned channel = 0; channel < channels_; ++channel) {
        if (std::filesystem::exists(sysfs_dir_ / ("pwm" + std::to_string(channel)))) {
            try {
                write_attribute(sysfs_dir_ / "unexport", std::to_string(channel));
            } catch (const std::exception&) {
                // Best effort: the next fixture's assertions show a channel left behind.
            }
        }
    }
}

PwmChannelState PwmSimChip::state(unsigned channel) const {
    std::istringstream lines(read_attribute(kDebugfs / "state"));
    const std::string prefix = "pwm" + std::to_string(channel) + " ";
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind(prefix, 0) == 0) {
            PwmChannelState state;
            state.requested = number(line, "requested") != 0;
            state.enabled = number(line, "enabled") != 0;
            state.period_ns = number(line, "period");
            state.duty_cycle_ns = number(line, "duty_cycle");
            state.inversed = field(line, "polarity") == "inversed";
            state.applies = number(line, "applies");
            return state;
        }
    }
    throw std::out_of_range("pwm-sim has no channel " + std::to_string(channel));
}

std::vector<PwmApplied> PwmSimChip::log() const {
    std::istringstream lines(read_attribute(kDebugfs / "log"));
    std::vector<PwmApplied> log;
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("dropped ", 0) == 0) {
            throw std::runtime_error("pwm-sim's log overflowed (" + line +
                                     "): clear it more often or load it with a larger log_size");
        }
        PwmApplied applied;
        std::uint64_t time_ns = 0;
        if (std::sscanf(line.c_str(), "%lu pwm%u", &time_ns, &applied.channel) != 2) {
            throw std::runtime_error("unexpected pwm-sim log line: " + line);
        }
        applied.time = std::chrono::steady_clock::time_point(std::chrono::nanoseconds(time_ns));
        applied.enabled = number(line, "enabled") != 0;
        applied.period_ns = number(line, "period");
        applied.duty_cycle_ns = number(line, "duty_cycle");
        applied.inversed = field(line, "polarity") == "inversed";
        log.push_back(applied);
    }
    return log;
}

void PwmSimChip::clear_log() const {
    write_attribute(kDebugfs / "log", "0");
}

}  // namespace vibscore::hil
