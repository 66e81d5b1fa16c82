#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vibscore::hil {

struct GpioSimOptions {
    unsigned lines = 4;
    std::string label;                    // the chip's label; empty: gpio-sim's own
    std::vector<std::string> line_names;  // names of lines 0.., may be shorter than `lines`
};

// A gpio-sim chip configured through configfs: a real /dev/gpiochipN that libgpiod can request
// lines of, whose driven values the test reads back. Removed again on destruction.
class GpioSimChip {
  public:
    explicit GpioSimChip(GpioSimOptions options = {});
    ~GpioSimChip();
    GpioSimChip(const GpioSimChip&) = delete;
    GpioSimChip& operator=(const GpioSimChip&) = delete;

    const std::filesystem::path& chip_path() const { return chip_path_; }  // /dev/gpiochipN
    const std::string& chip_name() const { return chip_name_; }            // gpiochipN
    unsigned lines() const { return lines_; }

    // The value a consumer drives on `line`; while no consumer holds it, the pull's value.
    int value(unsigned line) const;
    // What `line` reads as an input (and what it falls back to when released).
    void set_pull(unsigned line, bool up) const;
    // sim_gpioK/value in sysfs, for samplers.
    std::filesystem::path value_file(unsigned line) const;

  private:
    std::filesystem::path config_;  // /sys/kernel/config/gpio-sim/NAME
    std::filesystem::path sysfs_;   // /sys/devices/platform/gpio-sim.M/gpiochipN
    std::filesystem::path chip_path_;
    std::string chip_name_;
    unsigned lines_;
};

}  // namespace vibscore::hil
