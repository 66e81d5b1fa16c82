#pragma once

#include <map>
#include <memory>
#include <string>

#include "daemon/drivers/actuator.hpp"

namespace vibscore::drivers {

// The settings every backend takes, whatever its kind; the player enforces them.
struct CommonSettings {
    double max_on_time_s = 0.0;     // max-on-time-ms: thermal protection; 0 = no limit
    double pulse_period_s = 0.040;  // pulse-period-ms: on/off backends' pulse modulation
};

// Takes the common keys out of a driver's settings (the rest are the backend's own).
// Throws std::invalid_argument naming the driver, key and value.
CommonSettings take_common_settings(const std::string& driver,
                                    std::map<std::string, std::string>& settings);

// A backend with the common settings applied to what it reports: a configured maximum
// on-time tightens the backend's own, if it has one.
class ConfiguredActuator final : public Actuator {
  public:
    ConfiguredActuator(std::unique_ptr<Actuator> backend, CommonSettings common);

    std::string_view driver_name() const override { return backend_->driver_name(); }
    Capabilities capabilities() const override;
    void apply(const Drive& drive) override { backend_->apply(drive); }
    void off() noexcept override { backend_->off(); }
    void prepare(const Drive& next) override { backend_->prepare(next); }
    void set_gain(double gain) override { backend_->set_gain(gain); }
    void set_off_timer(double seconds) override { backend_->set_off_timer(seconds); }
    std::shared_ptr<sensors::Accelerometer> accelerometer() const override {
        return backend_->accelerometer();
    }
    bool take_declaration(const actuator::Declaration& declared) override {
        return backend_->take_declaration(declared);
    }

  private:
    std::unique_ptr<Actuator> backend_;
    CommonSettings common_;
};

}  // namespace vibscore::drivers
