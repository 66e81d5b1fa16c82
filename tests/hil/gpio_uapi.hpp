#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"

namespace vibscore::hil {

// The GPIO character device's uAPI v2 (linux/gpio.h) spoken directly, without libgpiod: how the
// hil tests see what the kernel holds for a line, whichever libgpiod generation vibscored was
// built with, and a consumer of their own that shares no code with the code under test.
// Errors are std::system_error naming the chip.

struct GpioChipInfo {
    std::string name;  // gpiochipN
    std::string label;
    unsigned lines = 0;
};

// What the kernel reports for one line (GPIO_V2_GET_LINEINFO_IOCTL).
struct GpioLineInfo {
    std::string name;
    std::string consumer;
    bool used = false;
    bool input = false;
    bool output = false;
    bool active_low = false;
    bool open_drain = false;
    bool open_source = false;
    bool pull_up = false;
    bool pull_down = false;
    bool bias_disabled = false;
};

GpioChipInfo gpio_chip_info(const std::filesystem::path& chip);
GpioLineInfo gpio_line_info(const std::filesystem::path& chip, unsigned offset);

// Lines requested through uAPI v2 (GPIO_V2_GET_LINE_IOCTL), without a bias, released when the
// object goes (or by release()).
class GpioUapiLines {
  public:
    enum class Direction { input, output };

    // Outputs start low.
    GpioUapiLines(const std::filesystem::path& chip, std::vector<unsigned> offsets,
                  Direction direction, const std::string& consumer = "vibscore-hil");

    // One value per line, in request order.
    void set_values(const std::vector<int>& values);
    std::vector<int> values() const;
    void release() { fd_.close(); }

  private:
    std::filesystem::path chip_;
    std::vector<unsigned> offsets_;
    UniqueFd fd_;
};

}  // namespace vibscore::hil
