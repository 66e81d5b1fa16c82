#pragma once

#include <string>

#include "daemon/actuator/declaration.hpp"

namespace vibscore::client {

// `--actuator FILE` (render, check): the actuator declared in FILE's [actuator] section (the
// daemon's vibscored.conf will do; other sections are skipped). Throws std::runtime_error naming
// the file and, for a bad section, its line, key and value.
actuator::Declaration load_actuator(const std::string& file);

}  // namespace vibscore::client
