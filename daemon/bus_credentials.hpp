#pragma once

#include <sdbus-c++/IConnection.h>
#include <sdbus-c++/IProxy.h>
#include <sys/types.h>

#include <memory>
#include <string>

namespace vibscore::daemon {

// A caller's user id as the bus driver knows it (org.freedesktop.DBus.GetConnectionUnixUser).
// Not sd-bus's sender credentials: those are augmented from /proc/PID, which the unit's
// ProtectProc=invisible hides from user vibscore for every other user's process.
class BusCredentials {
  public:
    explicit BusCredentials(sdbus::IConnection& connection);

    uid_t uid_of(const std::string& sender);

  private:
    std::unique_ptr<sdbus::IProxy> proxy_;
};

}  // namespace vibscore::daemon
