#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <string>
#include <vector>

#include "daemon/callers.hpp"
#include "daemon/drivers/available.hpp"
#include "daemon/player.hpp"
#include "daemon/registry/registry.hpp"
#include "haptics1-adaptor.h"

namespace vibscore::daemon {

inline constexpr const char* kBusName = "org.vibscore.Haptics1";
inline constexpr const char* kObjectPath = "/org/vibscore/Haptics1";

// Switching actuator backends at run time; main() owns the backends and the configuration.
class DriverControl {
  public:
    virtual ~DriverControl() = default;
    virtual std::vector<drivers::DriverInfo> drivers() const = 0;
    // Switches to `driver` with its configured settings; throws what opening it throws.
    virtual void switch_driver(const std::string& driver) = 0;
};

// The org.vibscore.Haptics1 object: checks who calls and what they send, then hands the work to
// the registry and the player. Every failure leaves here as a named D-Bus error; nothing a caller
// sends can stop the daemon.
class HapticsService final : public sdbus::AdaptorInterfaces<org::vibscore::Haptics1_adaptor>,
                             public PlayerListener {
  public:
    struct Settings {
        std::string driver;
        std::vector<std::string> capabilities;
        double separation_s = 0.030;
    };

    HapticsService(sdbus::IConnection& connection, Registry& registry, Player& player,
                   CallerDirectory& callers, DriverControl& driver_control, Settings settings);
    ~HapticsService() override;

    // New settings; a change of driver or capabilities is announced with PropertiesChanged.
    void update_settings(Settings settings);

    // PlayerListener: playback events become signals.
    void playback_started(std::uint64_t id, const std::string& label) override;
    void playback_position(std::uint64_t id, std::size_t bar, std::size_t symbol) override;
    void playback_finished(std::uint64_t id, const std::string& reason) override;

  private:
    std::uint64_t Play(const std::string& score,
                       const std::map<std::string, sdbus::Variant>& options) override;
    void Stop(const std::uint64_t& playback_id) override;
    void Compose(const std::string& name, const std::string& document) override;
    void Delete(const std::string& kind, const std::string& name) override;
    std::vector<sdbus::Struct<std::string, std::string>> List(const std::string& kind) override;
    std::string Get(const std::string& kind, const std::string& name) override;
    std::vector<sdbus::Struct<std::string, std::string>> ListDrivers() override;
    void SwitchDriver(const std::string& driver) override;
    std::string Driver() override { return settings_.driver; }
    std::vector<std::string> Capabilities() override { return settings_.capabilities; }
    double Intensity() override { return player_.master_intensity(); }
    void Intensity(const double& value) override;
    std::string Version() override;

    // The caller of the method being handled; counts the request against its rate.
    const Caller& admit_caller();
    void require_privileged(const Caller& caller, const char* action) const;
    PlaybackRequest prepare(const std::string& score,
                            const std::map<std::string, sdbus::Variant>& options,
                            const Caller& caller) const;

    Registry& registry_;
    Player& player_;
    CallerDirectory& callers_;
    DriverControl& driver_control_;
    Settings settings_;
};

}  // namespace vibscore::daemon
