#pragma once

#include <stdexcept>
#include <string>

#include "actuator/declaration.hpp"

namespace vibscore::client {

// `--actuator FILE` (render, check): the actuator declared in FILE's [actuator] section (the
// daemon's vibscored.conf will do, read by the daemon's rules: common/ini_reader.hpp; other
// sections are unused). Throws std::runtime_error naming the file and, for a bad line or section,
// its line, key and value.
actuator::Declaration load_actuator(const std::string& file);

// load_actuator's error for a file it cannot open: a failed operation (exit 1), as a missing
// score is, where a file with a bad section is a usage error.
class ActuatorFileUnreadable : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace vibscore::client
