#pragma once

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

// Requests `offsets` on `chip` (a number, a /dev path, a name such as gpiochip0, or a label:
// tried in that order) as outputs for consumer "vibscored", driven low, with the pull-down bias
// enabled, so that a line the kernel releases (the daemon killed or crashed) falls to low rather
// than keeping the level last driven (docs/drivers/gpio.md, "Safety"). The lines are driven low
// again and released when the object goes. Throws DeviceError naming the chip (and the lines)
// when the chip cannot be found or opened, or a line cannot be requested (missing, busy, not an
// output). Goes through libgpiod 1.x or 2.x, whichever the build found (gpio_lines_v1.cpp,
// gpio_lines_v2.cpp).
std::unique_ptr<GpioLines> open_gpio_lines(const std::string& chip,
                                           const std::vector<unsigned>& offsets);

// The libgpiod the daemon runs with, as the loaded library reports it: "libgpiod 2.2.1".
std::string gpio_library();

}  // namespace vibscore::drivers
