#include "daemon/actuator_config.hpp"

#include "daemon/config.hpp"

namespace vibscore::daemon {

std::optional<actuator::Declaration> declared_actuator(const DaemonConfig& config) {
    const auto header = config.section_lines.find(kActuatorSection);
    if (header == config.section_lines.end()) {
        return std::nullopt;
    }
    std::vector<actuator::Setting> settings;
    const auto lines = config.setting_lines.find(kActuatorSection);
    for (const auto& [key, value] : config.settings_of(kActuatorSection)) {
        std::string where;
        if (lines != config.setting_lines.end()) {
            if (const auto line = lines->second.find(key); line != lines->second.end()) {
                where = line->second;
            }
        }
        settings.push_back({key, value, where});
    }
    try {
        return actuator::parse_declaration(settings, header->second);
    } catch (const actuator::DeclarationError& error) {
        throw ConfigError(error.what());
    }
}

}  // namespace vibscore::daemon
