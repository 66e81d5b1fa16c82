#pragma once

#include <map>
#include <memory>
#include <string>

#include "common/event_loop.hpp"
#include "common/usage.hpp"
#include "daemon/player.hpp"
#include "daemon/virtual_vibra/ff_effect_player.hpp"
#include "daemon/virtual_vibra/uinput_ff_device.hpp"

namespace vibscore::daemon {

// vibscored.conf's [virtual-vibra] section (docs/feedbackd.md):
//   enabled = false        make the device (off unless asked for)
//   usage = notification   vibscored's usage of what it plays: decides arbitration
//   name = vibscore virtual vibra
//   effects-max = 16       effects a client may upload at once
struct VirtualVibraSettings {
    bool enabled = false;
    Usage usage = Usage::notification;
    std::string name = "vibscore virtual vibra";
    unsigned effects_max = 16;
};

// Throws std::invalid_argument naming the key and value at fault.
VirtualVibraSettings parse_virtual_vibra_settings(
    const std::map<std::string, std::string>& section);

// vibscore as the kernel's vibra: a uinput force-feedback device advertising rumble, periodic
// (sine, square, triangle), constant and gain, whose effects play on vibscored's actuator
// through the player. Its requests are answered on the daemon's loop. The device goes away
// (clients see it unplugged) with this object.
class VirtualVibra {
  public:
    // Throws DeviceError when the device cannot be made (no uinput).
    VirtualVibra(EventLoop& loop, PlayerAccess player, const VirtualVibraSettings& settings,
                 double separation_s, OnTimeLimit max_on_time = {});
    ~VirtualVibra();
    VirtualVibra(const VirtualVibra&) = delete;
    VirtualVibra& operator=(const VirtualVibra&) = delete;

    const std::filesystem::path& event_node() const { return device_.event_node(); }

  private:
    static int on_request(sd_event_source*, int, std::uint32_t, void* self);

    FfEffectPlayer effects_;
    UinputFfDevice device_;
    EventSourcePtr source_;
};

}  // namespace vibscore::daemon
