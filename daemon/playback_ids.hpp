#pragma once

#include <cstdint>
#include <filesystem>

namespace vibscore::daemon {

// The first playback id of this run of the daemon. Ids are unique across restarts, so that a
// client's Stop(id) can never end another run's playback: the high 32 bits are the run's number,
// counted in the file .playback-run of the store (written crash-safely before the first id is
// given out), the low 32 bits count the run's playbacks from 1. When the store cannot keep the
// number (read-only, full), the run's number is the realtime clock's seconds since 1970, and a
// warning says so. dbus/org.vibscore.Haptics1.xml documents it for clients.
std::uint64_t first_playback_id(const std::filesystem::path& store);

// The store's file that counts runs.
inline constexpr const char* kRunCounterFile = ".playback-run";

}  // namespace vibscore::daemon
