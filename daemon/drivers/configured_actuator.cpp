#include "daemon/drivers/configured_actuator.hpp"

#include <utility>

#include "daemon/drivers/driver_settings.hpp"

namespace vibscore::drivers {

CommonSettings take_common_settings(const std::string& driver,
                                    std::map<std::string, std::string>& settings) {
    std::map<std::string, std::string> common_keys;
    for (const char* key : kCommonSettingKeys) {
        if (auto found = settings.find(key); found != settings.end()) {
            common_keys.insert(settings.extract(found));
        }
    }
    DriverSettings read(driver, std::move(common_keys));
    CommonSettings common;
    common.max_on_time_s = read.number("max-on-time-ms", 0.0, 0.0, 3'600'000.0) / 1000.0;
    common.pulse_period_s =
        read.number("pulse-period-ms", common.pulse_period_s * 1000.0, 5.0, 1000.0) / 1000.0;
    return common;
}

ConfiguredActuator::ConfiguredActuator(std::unique_ptr<Actuator> backend, CommonSettings common)
    : backend_(std::move(backend)), common_(common) {}

Capabilities ConfiguredActuator::capabilities() const {
    Capabilities capabilities = backend_->capabilities();
    if (common_.max_on_time_s > 0.0 &&
        (capabilities.max_on_time_s == 0.0 || common_.max_on_time_s < capabilities.max_on_time_s)) {
        capabilities.max_on_time_s = common_.max_on_time_s;
    }
    capabilities.pulse_period_s = common_.pulse_period_s;
    return capabilities;
}

}  // namespace vibscore::drivers
