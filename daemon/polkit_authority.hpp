#pragma once

#include <sdbus-c++/IConnection.h>
#include <sdbus-c++/IProxy.h>

#include <memory>

#include "daemon/authority.hpp"

namespace vibscore::daemon {

// polkit's org.freedesktop.PolicyKit1.Authority on the system bus, called over D-Bus (no GLib):
// CheckAuthorization for the subject ("system-bus-name", {"name": sender}), without interaction.
// It shares the daemon's connection and never waits for polkit: the answer arrives as a reply on
// that connection, like any other message the bus thread serves.
class BusPolkitAuthority final : public PolkitAuthority {
  public:
    explicit BusPolkitAuthority(sdbus::IConnection& connection);

    void check(const std::string& sender, std::string_view action_id, Answered answered) override;

  private:
    std::unique_ptr<sdbus::IProxy> proxy_;
};

}  // namespace vibscore::daemon
