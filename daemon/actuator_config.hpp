#pragma once

#include <optional>

#include "actuator/declaration.hpp"

namespace vibscore::daemon {

struct DaemonConfig;

// The actuator [actuator] of vibscored.conf declares (docs/drivers.md), read from the section's
// lines as parse_config() keeps them; nothing without the section. Throws ConfigError
// "file:line: [actuator] key = "value": ..." naming the key and the value at fault.
std::optional<actuator::Declaration> declared_actuator(const DaemonConfig& config);

}  // namespace vibscore::daemon
