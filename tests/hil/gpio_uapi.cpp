#include "tests/hil/gpio_uapi.hpp"

#include <fcntl.h>
#include <linux/gpio.h>
#include <sys/ioctl.h>

#include <cstring>
#include <stdexcept>

#include "tests/hil/kernel_files.hpp"

namespace vibscore::hil {

namespace {

UniqueFd open_chip(const std::filesystem::path& chip) {
    UniqueFd fd(::open(chip.c_str(), O_RDWR | O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno("cannot open", chip);
    }
    return fd;
}

// A fixed-size, possibly unterminated name field of the uAPI.
template <std::size_t N>
std::string text(const char (&field)[N]) {
    return std::string(field, ::strnlen(field, N));
}

}  // namespace

GpioChipInfo gpio_chip_info(const std::filesystem::path& chip) {
    const auto fd = open_chip(chip);
    gpiochip_info info{};
    if (::ioctl(fd.get(), GPIO_GET_CHIPINFO_IOCTL, &info) != 0) {
        throw_errno("GPIO_GET_CHIPINFO_IOCTL on", chip);
    }
    return {text(info.name), text(info.label), info.lines};
}

GpioLineInfo gpio_line_info(const std::filesystem::path& chip, unsigned offset) {
    const auto fd = open_chip(chip);
    gpio_v2_line_info info{};
    info.offset = offset;
    if (::ioctl(fd.get(), GPIO_V2_GET_LINEINFO_IOCTL, &info) != 0) {
        throw_errno("GPIO_V2_GET_LINEINFO_IOCTL (line " + std::to_string(offset) + ") on", chip);
    }
    const auto has = [&info](std::uint64_t flag) { return (info.flags & flag) != 0; };
    GpioLineInfo result;
    result.name = text(info.name);
    result.consumer = text(info.consumer);
    result.used = has(GPIO_V2_LINE_FLAG_USED);
    result.input = has(GPIO_V2_LINE_FLAG_INPUT);
    result.output = has(GPIO_V2_LINE_FLAG_OUTPUT);
    result.active_low = has(GPIO_V2_LINE_FLAG_ACTIVE_LOW);
    result.open_drain = has(GPIO_V2_LINE_FLAG_OPEN_DRAIN);
    result.open_source = has(GPIO_V2_LINE_FLAG_OPEN_SOURCE);
    result.pull_up = has(GPIO_V2_LINE_FLAG_BIAS_PULL_UP);
    result.pull_down = has(GPIO_V2_LINE_FLAG_BIAS_PULL_DOWN);
    result.bias_disabled = has(GPIO_V2_LINE_FLAG_BIAS_DISABLED);
    return result;
}

GpioUapiLines::GpioUapiLines(const std::filesystem::path& chip, std::vector<unsigned> offsets,
                             Direction direction, const std::string& consumer)
    : chip_(chip), offsets_(std::move(offsets)) {
    if (offsets_.empty() || offsets_.size() > GPIO_V2_LINES_MAX ||
        consumer.size() >= GPIO_MAX_NAME_SIZE) {
        throw std::invalid_argument("GpioUapiLines: 1 to 64 lines and a consumer of < 32 bytes");
    }
    gpio_v2_line_request request{};
    for (std::size_t i = 0; i < offsets_.size(); ++i) {
        request.offsets[i] = offsets_[i];
    }
    request.num_lines = static_cast<std::uint32_t>(offsets_.size());
    std::memcpy(request.consumer, consumer.data(), consumer.size());
    request.config.flags =
        direction == Direction::output ? GPIO_V2_LINE_FLAG_OUTPUT : GPIO_V2_LINE_FLAG_INPUT;
    // Outputs start low (the kernel's default too; said here so that it does not depend on it).
    if (direction == Direction::output) {
        auto& attribute = request.config.attrs[request.config.num_attrs++];
        attribute.attr.id = GPIO_V2_LINE_ATTR_ID_OUTPUT_VALUES;
        attribute.attr.values = 0;
        attribute.mask = offsets_.size() == 64 ? ~0ULL : (1ULL << offsets_.size()) - 1;
    }
    const auto fd = open_chip(chip_);
    if (::ioctl(fd.get(), GPIO_V2_GET_LINE_IOCTL, &request) != 0) {
        throw_errno("GPIO_V2_GET_LINE_IOCTL on", chip_);
    }
    fd_ = UniqueFd(request.fd);
}

void GpioUapiLines::set_values(const std::vector<int>& values) {
    if (values.size() != offsets_.size()) {
        throw std::invalid_argument("GpioUapiLines::set_values: one value per line");
    }
    gpio_v2_line_values levels{};
    for (std::size_t i = 0; i < values.size(); ++i) {
        levels.mask |= 1ULL << i;
        levels.bits |= values[i] != 0 ? 1ULL << i : 0;
    }
    if (::ioctl(fd_.get(), GPIO_V2_LINE_SET_VALUES_IOCTL, &levels) != 0) {
        throw_errno("GPIO_V2_LINE_SET_VALUES_IOCTL on lines of", chip_);
    }
}

std::vector<int> GpioUapiLines::values() const {
    gpio_v2_line_values levels{};
    levels.mask = offsets_.size() == 64 ? ~0ULL : (1ULL << offsets_.size()) - 1;
    if (::ioctl(fd_.get(), GPIO_V2_LINE_GET_VALUES_IOCTL, &levels) != 0) {
        throw_errno("GPIO_V2_LINE_GET_VALUES_IOCTL on lines of", chip_);
    }
    std::vector<int> values;
    for (std::size_t i = 0; i < offsets_.size(); ++i) {
        values.push_back((levels.bits >> i) & 1 ? 1 : 0);
    }
    return values;
}

}  // namespace vibscore::hil
