// The part of open_gpio_lines() both libgpiod generations share: finding the chip, checking the
// lines, the error messages, and driving the lines low before they are released. The libgpiod
// calls themselves are in gpio_lines_v1.cpp or gpio_lines_v2.cpp (gpio_lines_chip.hpp).
#include "daemon/drivers/gpio_lines.hpp"

#include <algorithm>
#include <cerrno>
#include <exception>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "common/log.hpp"
#include "daemon/drivers/actuator.hpp"
#include "daemon/drivers/gpio_lines_chip.hpp"

namespace vibscore::drivers {

namespace {

constexpr const char* kConsumer = "vibscored";

class KernelGpioLines final : public GpioLines {
  public:
    KernelGpioLines(std::string description, std::size_t count,
                    std::unique_ptr<GpioLineRequest> request)
        : description_(std::move(description)), count_(count), request_(std::move(request)) {}

    KernelGpioLines(const KernelGpioLines&) = delete;
    KernelGpioLines& operator=(const KernelGpioLines&) = delete;

    ~KernelGpioLines() override {
        // Most controllers keep the last level after release, so leave them low on purpose.
        try {
            request_->set_values(std::vector<int>(count_, 0));
        } catch (const std::exception& error) {
            log::warning(description_ + ": cannot drive low on release: " + error.what());
        }
        try {
            request_->release();
        } catch (const std::exception& error) {
            log::warning(description_ + ": cannot release: " + error.what());
        }
    }

    std::size_t count() const override { return count_; }

    void set_values(const std::vector<int>& values) override {
        if (values.size() != count_) {
            throw std::invalid_argument(description_ + ": " + std::to_string(values.size()) +
                                        " values for " + std::to_string(count_) + " lines");
        }
        try {
            request_->set_values(values);
        } catch (const std::exception& error) {
            throw DeviceError(description_ + ": cannot set values: " + error.what());
        }
    }

    std::string describe() const override { return description_; }

  private:
    std::string description_;
    std::size_t count_;
    std::unique_ptr<GpioLineRequest> request_;
};

bool is_number(const std::string& text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// What the kernel's error means for opening a chip; errno's own text otherwise.
std::string reason(const std::system_error& error) {
    if (error.code() == std::errc::no_such_device ||
        error.code() == std::errc::inappropriate_io_control_operation) {
        return "not a GPIO chip (" + error.code().message() + ")";
    }
    return error.code().message();
}

struct FoundChip {
    std::unique_ptr<GpioChip> chip;
    std::filesystem::path path;
};

// The gpiochip* entries of `dev`, in name order.
std::vector<std::filesystem::path> chip_entries(const std::filesystem::path& dev) {
    std::vector<std::filesystem::path> entries;
    std::error_code error;
    for (std::filesystem::directory_iterator it(dev, error), end; !error && it != end;
         it.increment(error)) {
        if (it->path().filename().string().rfind("gpiochip", 0) == 0) {
            entries.push_back(it->path());
        }
    }
    std::sort(entries.begin(), entries.end());
    return entries;
}

// A number, a path or a name is opened directly; a name that is no entry of `dev` may still be
// a label (as libgpiod 1.x's OPEN_LOOKUP and 2.x's tools take them).
FoundChip find_chip(const std::string& chip, const std::filesystem::path& dev,
                    const GpioChipOpener& open) {
    if (chip.empty()) {
        throw DeviceError("GPIO chip \"\": an empty name names no chip");
    }
    const bool number = is_number(chip);
    const bool path = chip.front() == '/';
    const bool name = !number && !path && chip.find('/') == std::string::npos;
    std::filesystem::path direct;
    if (number) {
        // As libgpiod 1.x read it (strtoul): 07 is gpiochip7.
        const auto digits = chip.find_first_not_of('0');
        direct = dev / ("gpiochip" + (digits == std::string::npos ? "0" : chip.substr(digits)));
    } else if (path) {
        direct = chip;
    } else if (name) {
        direct = dev / chip;
    }
    if (!direct.empty()) {
        try {
            return {open(direct), direct};
        } catch (const std::system_error& error) {
            if (error.code() != std::errc::no_such_file_or_directory || !name) {
                throw DeviceError("GPIO chip " + chip + ": cannot open " + direct.string() + ": " +
                                  reason(error));
            }
        }
    }
    std::string chips;
    for (const auto& entry : chip_entries(dev)) {
        std::string label;
        try {
            auto candidate = open(entry);
            label = candidate->label();
            if (label == chip) {
                return {std::move(candidate), entry};
            }
            label = "\"" + label + "\"";
        } catch (const std::system_error& error) {
            label = "cannot open: " + reason(error);
        }
        chips += (chips.empty() ? "" : ", ") + entry.filename().string() + " " + label;
    }
    throw DeviceError(
        "GPIO chip " + chip +
        ": no such chip: " + (direct.empty() ? "" : "no " + direct.string() + " and ") +
        "no chip labelled \"" + chip + "\" (" +
        (chips.empty() ? "there is no GPIO chip in " + dev.string() : "the chips are " + chips) +
        ")");
}

// Why a request failed: who holds the lines when they are busy, the kernel's word otherwise.
std::string request_failure(const std::system_error& error, const GpioChip& chip,
                            const std::vector<unsigned>& offsets) {
    if (error.code() == std::errc::device_or_resource_busy) {
        std::string users;
        for (const unsigned offset : offsets) {
            std::optional<std::string> user;
            try {
                user = chip.user(offset);
            } catch (const std::exception&) {
                continue;  // the busy message without this line's user is still right
            }
            if (user) {
                users += (users.empty() ? "" : ", ") + std::string("line ") +
                         std::to_string(offset) + " is used by " +
                         (user->empty() ? "a consumer without a name" : "\"" + *user + "\"");
            }
        }
        if (!users.empty()) {
            return "busy: " + users + " (see gpioinfo)";
        }
    }
    return error.code().message();
}

}  // namespace

std::string describe_lines(const std::string& chip, const std::vector<unsigned>& offsets) {
    std::string text = chip + (offsets.size() == 1 ? " line " : " lines ");
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        text += (i == 0 ? "" : ", ") + std::to_string(offsets[i]);
    }
    return text;
}

std::unique_ptr<GpioLines> request_gpio_lines(const std::string& chip,
                                              const std::vector<unsigned>& offsets,
                                              const std::filesystem::path& dev,
                                              const GpioChipOpener& open) {
    const std::string description = describe_lines(chip, offsets);
    FoundChip found = find_chip(chip, dev, open);
    const std::string where = found.path.string();
    unsigned line_count = 0;
    try {
        line_count = found.chip->line_count();
    } catch (const std::exception& error) {
        throw DeviceError("GPIO chip " + chip + ": cannot read " + where + ": " + error.what());
    }
    for (const unsigned offset : offsets) {
        if (offset >= line_count) {
            throw DeviceError(describe_lines(chip, {offset}) + ": no such line: " + where +
                              (line_count == 0
                                   ? " has no lines"
                                   : " has lines 0 to " + std::to_string(line_count - 1)));
        }
    }
    std::unique_ptr<GpioLineRequest> request;
    try {
        request = found.chip->request_outputs(offsets, kConsumer);
    } catch (const std::system_error& error) {
        throw DeviceError(description + ": cannot request as output: " +
                          request_failure(error, *found.chip, offsets));
    } catch (const std::exception& error) {
        throw DeviceError(description + ": cannot request as output: " + error.what());
    }
    log::debug(description + ": requested on " + where + " through " + gpio_library());
    return std::make_unique<KernelGpioLines>(description, offsets.size(), std::move(request));
}

std::unique_ptr<GpioLines> open_gpio_lines(const std::string& chip,
                                           const std::vector<unsigned>& offsets) {
    return request_gpio_lines(chip, offsets, "/dev", open_gpiod_chip);
}

std::string gpio_library() {
    return "libgpiod " + gpiod_version();
}

}  // namespace vibscore::drivers
