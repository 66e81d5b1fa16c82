#pragma once

#include <sdbus-c++/IConnection.h>
#include <sdbus-c++/IProxy.h>

#include <memory>

#include "daemon/authority.hpp"

namespace vibscore::daemon {

// polkit's org.freedesktop.PolicyKit1.Authority on the system bus, called over D-Bus (no GLib):
// CheckAuthorization for the subject ("system-bus-name", {"name": sender}), without interaction.
// It shares the daemon's connection; each check waits for polkit's reply.
class BusPolkitAuthority final : public PolkitAuthority {
  public:
    explicit BusPolkitAuthority(sdbus::IConnection& connection);

    PolkitAnswer check(const std::string& sender, std::string_view action_id) override;

  private:
    std::unique_ptr<sdbus::IProxy> proxy_;
};

}  // namespace vibscore::daemon
