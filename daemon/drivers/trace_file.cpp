#include "daemon/drivers/trace_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <stdexcept>
#include <string>
#include <system_error>

namespace vibscore::drivers {

namespace {

constexpr char kHeader[] = "time_ns,amplitude,frequency_hz,response\n";

std::runtime_error failure(const std::filesystem::path& path, const char* what, int error) {
    return std::runtime_error("trace file " + path.string() + ": " + what + ": " +
                              std::generic_category().message(error));
}

}  // namespace

TraceFile::TraceFile(std::filesystem::path path) : path_(std::move(path)) {
    // Appended to, never truncated: `vibscored --safe-off` and the daemon systemd restarts after
    // a crash open the trace again, and the crashed run's record is what one wants to read.
    fd_ = UniqueFd(::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644));
    if (fd_.get() < 0) {
        throw failure(path_, "cannot open", errno);
    }
    struct stat status {};
    if (::fstat(fd_.get(), &status) != 0) {
        throw failure(path_, "cannot stat", errno);
    }
    if (!S_ISREG(status.st_mode) || status.st_size == 0) {
        write_line(kHeader, sizeof kHeader - 1);
    }
}

void TraceFile::record(std::int64_t time_ns, double amplitude, double frequency_hz,
                       double response) {
    // Room for an int64 and three shortest round-trip doubles (at most 24 characters each).
    std::array<char, 128> line;
    char* const end = line.data() + line.size();
    char* p = std::to_chars(line.data(), end, time_ns).ptr;
    for (const double value : {amplitude, frequency_hz, response}) {
        *p++ = ',';
        p = std::to_chars(p, end, value).ptr;
    }
    *p++ = '\n';
    write_line(line.data(), static_cast<std::size_t>(p - line.data()));
}

void TraceFile::write_line(const char* data, std::size_t size) {
    ssize_t written;
    do {
        written = ::write(fd_.get(), data, size);
    } while (written < 0 && errno == EINTR);
    if (written < 0) {
        throw failure(path_, "cannot write", errno);
    }
    if (static_cast<std::size_t>(written) != size) {
        // A regular file is written short only when the disk or the quota is full.
        throw failure(path_, "short write", ENOSPC);
    }
}

}  // namespace vibscore::drivers
