#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string_view>
#include <vector>

// Crash-safe file updates for the registry's store. A reader after a crash at any instant (power
// loss included) finds either the old content or the new one, never a mixture or a prefix.
// Failures throw std::system_error whose message names the path and the errno text.
namespace vibscore::daemon {

// Replaces the file at path with content: writes a temporary file in the same directory (its
// name starts with '.' and contains ".tmp-"), fsyncs it, renames it over path and fsyncs the
// directory. When it returns, the new content is durable. On failure the temporary file is
// removed and the old content, if any, is untouched.
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           ::mode_t mode = 0644);

// Unlinks path and fsyncs its directory so the removal survives a crash. Returns false when
// there was no such file.
bool remove_file_durably(const std::filesystem::path& path);

// fsyncs a directory, making renames and unlinks inside it durable.
void sync_directory(const std::filesystem::path& directory);

// Whether a file name (not a path) is a temporary file of write_file_atomically.
bool is_temporary_file_name(std::string_view file_name);

// Deletes the temporaries an interrupted write_file_atomically left in directory. Returns the
// paths it removed.
std::vector<std::filesystem::path> remove_stale_temporaries(const std::filesystem::path& directory);

}  // namespace vibscore::daemon
