// gpio_lines_chip.hpp on libgpiod 1.x (Debian 12), which speaks the kernel's GPIO uAPI v1.
#include <gpiod.h>

#include <gpiod.hpp>

#include "daemon/drivers/gpio_lines_chip.hpp"

namespace vibscore::drivers {

namespace {

class V1LineRequest final : public GpioLineRequest {
  public:
    explicit V1LineRequest(gpiod::line_bulk lines) : lines_(std::move(lines)) {}

    void set_values(const std::vector<int>& values) override { lines_.set_values(values); }
    void release() override { lines_.release(); }

  private:
    gpiod::line_bulk lines_;  // each line keeps its chip open
};

class V1Chip final : public GpioChip {
  public:
    explicit V1Chip(const std::filesystem::path& path)
        : chip_(path.string(), gpiod::chip::OPEN_BY_PATH) {}

    std::string name() const override { return chip_.name(); }
    std::string label() const override { return chip_.label(); }
    unsigned line_count() const override { return chip_.num_lines(); }

    std::optional<std::string> user(unsigned offset) const override {
        auto line = chip_.get_line(offset);
        line.update();
        if (!line.is_used()) {
            return std::nullopt;
        }
        return line.consumer();
    }

    std::unique_ptr<GpioLineRequest> request_outputs(const std::vector<unsigned>& offsets,
                                                     const std::string& consumer) override {
        gpiod::line_request request;
        request.consumer = consumer;
        request.request_type = gpiod::line_request::DIRECTION_OUTPUT;
        request.flags = gpiod::line_request::FLAG_BIAS_PULL_DOWN;
        auto lines = chip_.get_lines(offsets);
        lines.request(request, std::vector<int>(offsets.size(), 0));
        return std::make_unique<V1LineRequest>(std::move(lines));
    }

  private:
    gpiod::chip chip_;
};

}  // namespace

std::unique_ptr<GpioChip> open_gpiod_chip(const std::filesystem::path& path) {
    return std::make_unique<V1Chip>(path);
}

std::string gpiod_version() {
    return gpiod_version_string();
}

}  // namespace vibscore::drivers
