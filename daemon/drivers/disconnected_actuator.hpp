#pragma once

#include <string>
#include <utility>

#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

// What the player holds while no backend could be opened (after a failed driver switch whose
// previous backend would not reopen either): every playback fails with the reason, and the
// daemon keeps serving until a switch or a reload succeeds.
class DisconnectedActuator final : public Actuator {
  public:
    explicit DisconnectedActuator(std::string reason) : reason_(std::move(reason)) {}

    std::string_view driver_name() const override { return "none"; }
    Capabilities capabilities() const override { return {}; }
    void apply(const Drive&) override { throw DeviceError("no actuator: " + reason_); }
    void off() noexcept override {}

  private:
    std::string reason_;
};

}  // namespace vibscore::drivers
