#pragma once

#include <chrono>
#include <filesystem>
#include <string>

namespace vibscore::hil {

// Small helpers over the kernel's text files (sysfs, configfs, debugfs). They throw
// std::system_error naming the file, so a failing fixture says what the kernel refused.

// Writes `value` with one write(), as the kernel attribute expects.
void write_attribute(const std::filesystem::path& file, const std::string& value);
// The whole content, without the trailing newline.
std::string read_attribute(const std::filesystem::path& file);
// Polls until `path` exists; throws std::runtime_error naming it after `timeout`.
void wait_for_path(const std::filesystem::path& path,
                   std::chrono::milliseconds timeout = std::chrono::seconds(5));
// errno as a std::system_error: "<what> <path>: <strerror>".
[[noreturn]] void throw_errno(const std::string& what, const std::filesystem::path& path);

}  // namespace vibscore::hil
