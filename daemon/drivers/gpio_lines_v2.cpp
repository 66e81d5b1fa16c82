// gpio_lines_chip.hpp on libgpiod 2.x (Debian 13), which speaks the kernel's GPIO uAPI v2.
#include <gpiod.hpp>

#include "daemon/drivers/gpio_lines_chip.hpp"

namespace vibscore::drivers {

namespace {

class V2LineRequest final : public GpioLineRequest {
  public:
    V2LineRequest(gpiod::line_request request, gpiod::line::offsets offsets)
        : request_(std::move(request)), offsets_(std::move(offsets)) {}

    void set_values(const std::vector<int>& values) override {
        gpiod::line::values levels;
        levels.reserve(values.size());
        for (const int value : values) {
            levels.push_back(value != 0 ? gpiod::line::value::ACTIVE
                                        : gpiod::line::value::INACTIVE);
        }
        // By offset, not by position: the request's own order is libgpiod's business.
        request_.set_values(offsets_, levels);
    }

    void release() override { request_.release(); }

  private:
    gpiod::line_request request_;  // holds its own file descriptor: the chip may close
    gpiod::line::offsets offsets_;
};

class V2Chip final : public GpioChip {
  public:
    explicit V2Chip(const std::filesystem::path& path) : chip_(path) {}

    std::string name() const override { return chip_.get_info().name(); }
    std::string label() const override { return chip_.get_info().label(); }
    unsigned line_count() const override {
        return static_cast<unsigned>(chip_.get_info().num_lines());
    }

    std::optional<std::string> user(unsigned offset) const override {
        const auto info = chip_.get_line_info(offset);
        if (!info.used()) {
            return std::nullopt;
        }
        return info.consumer();
    }

    std::unique_ptr<GpioLineRequest> request_outputs(const std::vector<unsigned>& offsets,
                                                     const std::string& consumer) override {
        const gpiod::line::offsets lines(offsets.begin(), offsets.end());
        auto request =
            chip_.prepare_request()
                .set_consumer(consumer)
                .add_line_settings(lines, gpiod::line_settings()
                                              .set_direction(gpiod::line::direction::OUTPUT)
                                              .set_bias(gpiod::line::bias::PULL_DOWN)
                                              .set_output_value(gpiod::line::value::INACTIVE))
                .do_request();
        return std::make_unique<V2LineRequest>(std::move(request), lines);
    }

  private:
    gpiod::chip chip_;
};

}  // namespace

std::unique_ptr<GpioChip> open_gpiod_chip(const std::filesystem::path& path) {
    return std::make_unique<V2Chip>(path);
}

std::string gpiod_version() {
    return gpiod::api_version();
}

}  // namespace vibscore::drivers
