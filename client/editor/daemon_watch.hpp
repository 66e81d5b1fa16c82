#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <mutex>
#include <optional>
#include <set>
#include <string>

namespace vibscore::client {

// Watches vibscored's name on the bus, so that a client waiting for PlaybackFinished notices
// when the daemon that plays for it dies (SIGKILL, a crash: it sends nothing) or is replaced
// by a restart. Signals may arrive on another thread than the one asking gone().
class DaemonWatch {
  public:
    // Starts watching at once; call follow() after each Play.
    explicit DaemonWatch(sdbus::IConnection& connection);

    // The daemon that owns the name now is the one that answered the last Play.
    void follow();

    // Why the followed daemon is no longer there ("vibscored left the bus", "vibscored was
    // restarted"); nullopt while it is.
    std::optional<std::string> gone();

  private:
    sdbus::IConnection& connection_;
    std::mutex mutex_;
    std::string owner_;           // the followed daemon's unique name; empty: none
    std::set<std::string> left_;  // unique names that have left the service's name
    bool restarted_ = false;      // a new owner took the name after owner_ left
    // Last, so it goes first: releasing it waits for a callback running on the event loop's
    // thread (sdbus-c++ holds one lock while it dispatches and while it releases a slot), and
    // none runs after it. Declared before the state, a NameOwnerChanged that came as the watch
    // was destroyed wrote into a set already destroyed.
    sdbus::Slot match_;
};

}  // namespace vibscore::client
