#include "tests/hil/gpio_lines_sampler.hpp"

#include <algorithm>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "common/unique_fd.hpp"
#include "tests/support/pace.hpp"

namespace vibscore::hil {

GpioLinesSampler::GpioLinesSampler(const GpioSimChip& chip, std::vector<unsigned> lines,
                                   std::chrono::microseconds period) {
    std::vector<std::filesystem::path> files;
    for (const unsigned line : lines) {
        files.push_back(chip.value_file(line));
    }
    thread_ = std::thread([this, files, period] { run(files, period); });
    std::unique_lock lock(mutex_);
    first_sample_.wait(lock, [this] { return !changes_.empty() || error_ != 0; });
    if (error_ != 0) {
        lock.unlock();
        thread_.join();
        throw std::system_error(error_, std::generic_category(),
                                "cannot sample the lines of " + chip.chip_name());
    }
}

GpioLinesSampler::~GpioLinesSampler() {
    stop_ = true;
    thread_.join();
}

void GpioLinesSampler::run(const std::vector<std::filesystem::path>& files,
                           std::chrono::microseconds period) {
    std::vector<UniqueFd> fds;
    for (const auto& file : files) {
        fds.emplace_back(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
        if (fds.back().get() < 0) {
            fail(errno);
            return;
        }
    }
    // One round of reads; false when a read failed (the thread then stops).
    const auto read_round = [&](std::vector<int>& values) {
        for (std::size_t i = 0; i < fds.size(); ++i) {
            char text[8];
            // sysfs regenerates an attribute's text on every read from offset 0.
            const auto got = ::pread(fds[i].get(), text, sizeof text, 0);
            if (got <= 0) {
                fail(got < 0 ? errno : EIO);
                return false;
            }
            values[i] = text[0] == '1' ? 1 : 0;
        }
        return true;
    };
    std::vector<int> first(fds.size()), second(fds.size()), last;
    auto before = std::chrono::steady_clock::now();
    while (!stop_) {
        if (!read_round(first)) {
            return;
        }
        const auto now = std::chrono::steady_clock::now();
        if (!read_round(second)) {
            return;
        }
        if (first != second) {
            ++torn_;
            continue;  // read again at once: the change is what matters
        }
        ++samples_;
        if (first != last) {
            std::lock_guard lock(mutex_);
            changes_.push_back({before, now, first});
            last = first;
            first_sample_.notify_all();
        }
        before = now;
        // The sampling period: the instrument's own rate, not a wait for anything.
        vibscore::testing::pace_for(period);
    }
}

void GpioLinesSampler::fail(int error) {
    std::lock_guard lock(mutex_);
    error_ = error;
    first_sample_.notify_all();
}

std::vector<LinesState> GpioLinesSampler::changes() const {
    std::lock_guard lock(mutex_);
    return changes_;
}

std::chrono::nanoseconds GpioLinesSampler::high_time(
    std::size_t index, std::chrono::steady_clock::time_point begin,
    std::chrono::steady_clock::time_point end) const {
    const auto states = changes();
    std::chrono::nanoseconds high{0};
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (states[i].values.at(index) != 1) {
            continue;
        }
        const auto from = std::max(states[i].seen, begin);
        const auto to = std::min(i + 1 < states.size() ? states[i + 1].seen : end, end);
        if (to > from) {
            high += to - from;
        }
    }
    return high;
}

}  // namespace vibscore::hil
