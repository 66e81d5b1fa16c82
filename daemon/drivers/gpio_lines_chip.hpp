#pragma once

// The few libgpiod calls open_gpio_lines() makes, without a libgpiod type: each libgpiod
// generation implements them in its own file (gpio_lines_v1.cpp for 1.x, which speaks the
// kernel's GPIO uAPI v1; gpio_lines_v2.cpp for 2.x, uAPI v2), and meson builds the one it finds.
// Everything else (finding the chip, the error messages, driving low before the release) is
// written once in gpio_lines.cpp on top of these, where unit tests reach it with a fake chip.
// Errors are std::system_error carrying the errno the kernel gave.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "daemon/drivers/gpio_lines.hpp"

namespace vibscore::drivers {

// Lines held by one request.
class GpioLineRequest {
  public:
    virtual ~GpioLineRequest() = default;
    // One value per line, in request order; 0 low, anything else high.
    virtual void set_values(const std::vector<int>& values) = 0;
    virtual void release() = 0;
};

// An open GPIO chip character device.
class GpioChip {
  public:
    virtual ~GpioChip() = default;
    virtual std::string name() const = 0;   // "gpiochip0"
    virtual std::string label() const = 0;  // what its driver calls it, e.g. "pinctrl-bcm2711"
    virtual unsigned line_count() const = 0;
    // Who holds line `offset`: nothing when it is free, the consumer's name (possibly empty)
    // when it is requested.
    virtual std::optional<std::string> user(unsigned offset) const = 0;
    // Requests `offsets` as outputs for `consumer`, driven low from the moment the request is
    // granted, with the pull-down bias.
    virtual std::unique_ptr<GpioLineRequest> request_outputs(const std::vector<unsigned>& offsets,
                                                             const std::string& consumer) = 0;
};

using GpioChipOpener = std::function<std::unique_ptr<GpioChip>(const std::filesystem::path&)>;

// Opens the chip at `path` with the libgpiod this build uses.
std::unique_ptr<GpioChip> open_gpiod_chip(const std::filesystem::path& path);

// The version the loaded libgpiod reports, e.g. "2.2.1".
std::string gpiod_version();

// open_gpio_lines() with the device directory and the way chips are opened given: a number N
// is `dev`/gpiochipN, an absolute path is itself, a name is `dev`/NAME, and otherwise the chip
// whose label it is, among the gpiochip* entries of `dev`.
std::unique_ptr<GpioLines> request_gpio_lines(const std::string& chip,
                                              const std::vector<unsigned>& offsets,
                                              const std::filesystem::path& dev,
                                              const GpioChipOpener& open);

}  // namespace vibscore::drivers
