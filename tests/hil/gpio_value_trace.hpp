#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "tests/hil/gpio_sim_chip.hpp"

namespace vibscore::hil {

// One value the GPIO core set on a line: the kernel's gpio:gpio_value trace event.
struct GpioValueSet {
    unsigned line;  // offset on the chip
    int value;
    bool operator==(const GpioValueSet&) const = default;
};

// "line 2 = 1", for test messages.
inline std::ostream& operator<<(std::ostream& out, const GpioValueSet& set) {
    return out << "line " << set.line << " = " << set.value;
}

// Every value the kernel's GPIO core sets on the lines of a gpio-sim chip, in order, from the
// gpio:gpio_value trace event in a tracing instance of its own (tracefs under debugfs). It sees
// what sampling the lines cannot: a level held for microseconds, such as the low that a consumer
// sets just before it releases a line (gpio-sim's line then takes its pull at once). The
// kernel traces the value of an output request, and every set through the character device.
class GpioValueTrace {
  public:
    explicit GpioValueTrace(const GpioSimChip& chip);
    ~GpioValueTrace();
    GpioValueTrace(const GpioValueTrace&) = delete;
    GpioValueTrace& operator=(const GpioValueTrace&) = delete;

    // The sets so far, oldest first.
    std::vector<GpioValueSet> sets() const;

  private:
    std::filesystem::path instance_;  // .../tracing/instances/NAME
    unsigned base_ = 0;               // the chip's first global GPIO number
    unsigned lines_ = 0;
};

}  // namespace vibscore::hil
