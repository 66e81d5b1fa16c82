#include "daemon/virtual_vibra/virtual_vibra.hpp"

#include <sys/epoll.h>

#include <stdexcept>

#include "common/log.hpp"
#include "common/quoted_text.hpp"
#include "daemon/drivers/driver_settings.hpp"
#include "daemon/drivers/evdev_discovery.hpp"

namespace vibscore::daemon {

namespace {

UinputFfSetup device_setup(const VirtualVibraSettings& settings) {
    return {settings.name,
            drivers::kVirtualVibraPhys,
            {FF_RUMBLE, FF_PERIODIC, FF_SINE, FF_SQUARE, FF_TRIANGLE, FF_CONSTANT, FF_GAIN},
            settings.effects_max};
}

}  // namespace

VirtualVibraSettings parse_virtual_vibra_settings(
    const std::map<std::string, std::string>& section) {
    drivers::DriverSettings read("virtual-vibra", section);
    VirtualVibraSettings settings;
    settings.enabled = read.flag("enabled", settings.enabled);
    const auto usage = read.text("usage", std::string(to_string(settings.usage)));
    if (!parse_usage(usage)) {
        throw std::invalid_argument("virtual-vibra setting usage = " + quoted_text(usage) +
                                    ": expected " + std::string(usage_names()));
    }
    settings.usage = *parse_usage(usage);
    settings.name = read.text("name", settings.name);
    settings.effects_max = static_cast<unsigned>(read.integer("effects-max", 16, 1, 64));
    read.reject_unknown();
    return settings;
}

VirtualVibra::VirtualVibra(EventLoop& loop, PlayerAccess player,
                           const VirtualVibraSettings& settings, double separation_s,
                           OnTimeLimit max_on_time)
    : effects_(std::move(player), settings.usage, separation_s, std::move(max_on_time)),
      device_(device_setup(settings), effects_) {
    sd_event_source* source = nullptr;
    if (sd_event_add_io(loop.get(), &source, device_.fd(), EPOLLIN, &VirtualVibra::on_request,
                        this) < 0) {
        throw std::runtime_error("cannot watch the virtual vibra's requests");
    }
    source_.reset(source);
    log::info("virtual vibra " + device_.event_node().string() + " (\"" + settings.name +
              "\"), usage " + std::string(to_string(settings.usage)));
}

VirtualVibra::~VirtualVibra() {
    source_.reset();
    log::info("virtual vibra " + device_.event_node().string() + " removed");
}

int VirtualVibra::on_request(sd_event_source*, int, std::uint32_t, void* self) {
    auto* vibra = static_cast<VirtualVibra*>(self);
    try {
        vibra->device_.service();
    } catch (const std::exception& error) {
        // Nothing a client does can stop the daemon; the device keeps its other clients.
        log::error(std::string("virtual vibra: ") + error.what());
    }
    return 0;
}

}  // namespace vibscore::daemon
