#pragma once

#include <gpiod.hpp>

#include <memory>
#include <string>
#include <vector>

namespace vibscore::drivers {

// The GPIO output lines one actuator drives, requested together: the only kernel calls the GPIO
// backends make. Tests put a fake behind it that records what was set and when.
class GpioLines {
  public:
    virtual ~GpioLines() = default;

    // How many lines were requested; set_values() takes one value per line, in request order.
    virtual std::size_t count() const = 0;

    // Sets every line at once: 0 low, anything else high. Throws DeviceError naming the chip and
    // the lines when the kernel refuses.
    virtual void set_values(const std::vector<int>& values) = 0;

    // The chip and lines for messages, e.g. "gpiochip0 lines 17, 18".
    virtual std::string describe() const = 0;
};

// "gpiochip0 line 17" or "gpiochip0 lines 17, 18".
std::string describe_lines(const std::string& chip, const std::vector<unsigned>& offsets);

// The request open_gpio_lines() makes: outputs for consumer "vibscored", with the pull-down bias
// enabled, so that a line the kernel releases (the daemon killed or crashed) falls to low rather
// than keeping the level last driven (docs/drivers/gpio.md, "Safety").
gpiod::line_request output_line_request();

// Requests `offsets` on `chip` (a name such as gpiochip0, a /dev path, a label or a number) as
// outputs driven low, with output_line_request(). The lines are driven low again and released when
// the object goes. Throws DeviceError naming the chip (and the lines) when the chip cannot be
// opened or a line cannot be requested (missing, busy, not an output).
std::unique_ptr<GpioLines> open_gpio_lines(const std::string& chip,
                                           const std::vector<unsigned>& offsets);

}  // namespace vibscore::drivers
