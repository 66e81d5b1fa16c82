#include "tests/hil/kernel_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "common/unique_fd.hpp"
#include "tests/support/wait_until.hpp"

namespace vibscore::hil {

void throw_errno(const std::string& what, const std::filesystem::path& path) {
    throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

void write_attribute(const std::filesystem::path& file, const std::string& value) {
    const UniqueFd fd(::open(file.c_str(), O_WRONLY | O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno("cannot open", file);
    }
    const auto written = ::write(fd.get(), value.data(), value.size());
    if (written != static_cast<ssize_t>(value.size())) {
        throw_errno("cannot write \"" + value + "\" to", file);
    }
}

std::string read_attribute(const std::filesystem::path& file) {
    const UniqueFd fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno("cannot open", file);
    }
    std::string text;
    char buffer[4096];
    for (;;) {
        const auto got = ::read(fd.get(), buffer, sizeof buffer);
        if (got < 0) {
            throw_errno("cannot read", file);
        }
        if (got == 0) {
            break;
        }
        text.append(buffer, static_cast<std::size_t>(got));
    }
    if (!text.empty() && text.back() == '\n') {
        text.pop_back();
    }
    return text;
}

void wait_for_path(const std::filesystem::path& path, std::chrono::milliseconds timeout) {
    if (!vibscore::testing::wait_until([&] { return std::filesystem::exists(path); }, timeout,
                                       std::chrono::milliseconds(2))) {
        throw std::runtime_error(path.string() + " did not appear within " +
                                 std::to_string(timeout.count()) + " ms");
    }
}

}  // namespace vibscore::hil
