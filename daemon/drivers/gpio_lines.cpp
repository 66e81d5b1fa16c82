#include "daemon/drivers/gpio_lines.hpp"

#include <gpiod.hpp>

#include <exception>
#include <utility>

#include "daemon/drivers/actuator.hpp"
#include "daemon/log.hpp"

namespace vibscore::drivers {

namespace {

constexpr const char* kConsumer = "vibscored";

class KernelGpioLines final : public GpioLines {
  public:
    KernelGpioLines(const std::string& chip, const std::vector<unsigned>& offsets)
        : description_(describe_lines(chip, offsets)) {
        try {
            chip_.open(chip, gpiod::chip::OPEN_LOOKUP);
        } catch (const std::exception& error) {
            throw DeviceError("GPIO chip " + chip + ": cannot open: " + error.what());
        }
        try {
            lines_ = chip_.get_lines(offsets);
            // Low from the moment the request is granted: nothing vibrates at start-up.
            lines_.request(output_line_request(), std::vector<int>(offsets.size(), 0));
        } catch (const std::exception& error) {
            throw DeviceError(description_ + ": cannot request as output: " + error.what());
        }
    }

    KernelGpioLines(const KernelGpioLines&) = delete;
    KernelGpioLines& operator=(const KernelGpioLines&) = delete;

    ~KernelGpioLines() override {
        // Most controllers keep the last level after release, so leave them low on purpose.
        try {
            lines_.set_values(std::vector<int>(lines_.size(), 0));
            lines_.release();
        } catch (const std::exception& error) {
            log::warning(description_ + ": cannot drive low on release: " + error.what());
        }
    }

    std::size_t count() const override { return lines_.size(); }

    void set_values(const std::vector<int>& values) override {
        try {
            lines_.set_values(values);
        } catch (const std::exception& error) {
            throw DeviceError(description_ + ": cannot set values: " + error.what());
        }
    }

    std::string describe() const override { return description_; }

  private:
    std::string description_;
    gpiod::chip chip_;
    gpiod::line_bulk lines_;
};

}  // namespace

gpiod::line_request output_line_request() {
    gpiod::line_request request;
    request.consumer = kConsumer;
    request.request_type = gpiod::line_request::DIRECTION_OUTPUT;
    request.flags = gpiod::line_request::FLAG_BIAS_PULL_DOWN;
    return request;
}

std::string describe_lines(const std::string& chip, const std::vector<unsigned>& offsets) {
    std::string text = chip + (offsets.size() == 1 ? " line " : " lines ");
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        text += (i == 0 ? "" : ", ") + std::to_string(offsets[i]);
    }
    return text;
}

std::unique_ptr<GpioLines> open_gpio_lines(const std::string& chip,
                                           const std::vector<unsigned>& offsets) {
    return std::make_unique<KernelGpioLines>(chip, offsets);
}

}  // namespace vibscore::drivers
