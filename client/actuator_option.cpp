#include "client/actuator_option.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vibscore::client {

actuator::Declaration load_actuator(const std::string& file) {
    std::ifstream in(file);
    if (!in) {
        throw ActuatorFileUnreadable(file + ": cannot open: " + std::strerror(errno));
    }
    std::ostringstream text;
    text << in.rdbuf();
    try {
        if (auto declaration = actuator::read_declaration(text.str(), file)) {
            return *declaration;
        }
    } catch (const actuator::DeclarationError& error) {
        throw std::runtime_error(error.what());
    }
    throw std::runtime_error(file +
                             ": has no [actuator] section (docs/drivers.md, \"Declaring "
                             "the actuator\")");
}

}  // namespace vibscore::client
