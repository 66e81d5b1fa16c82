#include "common/atomic_file.hpp"

#include "common/unique_fd.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <system_error>
#include <utility>

namespace vibscore::daemon {

namespace {

[[noreturn]] void throw_errno(int error, const std::filesystem::path& path, std::string_view what) {
    throw std::system_error(error, std::generic_category(),
                            path.string() + ": " + std::string(what));
}

// A temporary file that is unlinked unless it was renamed into place.
class TemporaryFile {
  public:
    explicit TemporaryFile(std::filesystem::path path) : path_(std::move(path)) {}
    ~TemporaryFile() {
        if (!path_.empty()) {
            ::unlink(path_.c_str());
        }
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const std::filesystem::path& path() const { return path_; }
    void release() { path_.clear(); }

  private:
    std::filesystem::path path_;
};

constexpr std::string_view temporary_marker = ".tmp-";

void write_all(int fd, std::string_view content, const std::filesystem::path& path) {
    while (!content.empty()) {
        const auto written = ::write(fd, content.data(), content.size());
        if (written < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw_errno(errno, path, "write failed");
        }
        content.remove_prefix(static_cast<std::size_t>(written));
    }
}

void sync_fd(int fd, const std::filesystem::path& path) {
    if (::fsync(fd) != 0) {
        throw_errno(errno, path, "fsync failed");
    }
}

std::filesystem::path directory_of(const std::filesystem::path& path) {
    return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

}  // namespace

void sync_directory(const std::filesystem::path& directory) {
    const UniqueFd fd(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno(errno, directory, "cannot open directory");
    }
    sync_fd(fd.get(), directory);
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           ::mode_t mode) {
    const auto directory = directory_of(path);
    // The temporary lives in the target's directory because rename is atomic only within one
    // file system; the leading '.' keeps it out of the registry's "*.xml" scans.
    std::string name_template =
        (directory / ("." + path.filename().string() + std::string(temporary_marker) + "XXXXXX"))
            .string();
    UniqueFd fd(::mkostemp(name_template.data(), O_CLOEXEC));
    if (fd.get() < 0) {
        throw_errno(errno, path,
                    "cannot create a temporary file in " + directory.string() + " to write it");
    }
    TemporaryFile temporary(name_template);

    write_all(fd.get(), content, temporary.path());
    // mkostemp creates the file 0600; the target gets the requested mode instead.
    if (::fchmod(fd.get(), mode) != 0) {
        throw_errno(errno, temporary.path(), "fchmod failed");
    }
    // The data must be on disk before the rename is, or a crash could leave the new name
    // pointing at an empty or partial file.
    sync_fd(fd.get(), temporary.path());
    if (const int error = fd.close(); error != 0) {
        throw_errno(error, temporary.path(), "close failed");
    }

    if (::rename(temporary.path().c_str(), path.c_str()) != 0) {
        throw_errno(errno, path, "cannot rename " + temporary.path().string() + " over it");
    }
    temporary.release();
    sync_directory(directory);
}

bool remove_file_durably(const std::filesystem::path& path) {
    if (::unlink(path.c_str()) != 0) {
        if (errno == ENOENT) {
            return false;
        }
        throw_errno(errno, path, "cannot remove");
    }
    sync_directory(directory_of(path));
    return true;
}

bool is_temporary_file_name(std::string_view file_name) {
    return file_name.starts_with('.') && file_name.find(temporary_marker) != std::string_view::npos;
}

std::vector<std::filesystem::path> remove_stale_temporaries(
    const std::filesystem::path& directory) {
    std::vector<std::filesystem::path> removed;
    std::error_code error;
    std::filesystem::directory_iterator entries(directory, error);
    if (error) {
        throw std::system_error(error, directory.string() + ": cannot list");
    }
    for (const auto& entry : entries) {
        if (!is_temporary_file_name(entry.path().filename().string())) {
            continue;
        }
        if (::unlink(entry.path().c_str()) != 0) {
            throw_errno(errno, entry.path(), "cannot remove stale temporary file");
        }
        removed.push_back(entry.path());
    }
    if (!removed.empty()) {
        sync_directory(directory);
    }
    return removed;
}

}  // namespace vibscore::daemon
