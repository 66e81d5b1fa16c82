#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "actuator/declaration.hpp"
#include "client/clef_search.hpp"

namespace vibscore::client {

// vibscore show DOCUMENT --svg FILE | --png FILE: a score's staff, or a clef's strings and
// numbers. DOCUMENT is a VibScore or VibClef file, or a registry name: a score of vibscored's
// registry, else a clef found by the clef rule (`clefs`). With `actuator` (a clef only), its
// response is drawn behind the clef. Returns an exit code.
int show_picture(const std::string& document, const std::string& svg, const std::string& png,
                 const ClefSearch& clefs, std::ostream& out, std::ostream& err,
                 const std::optional<actuator::Declaration>& actuator = std::nullopt);

}  // namespace vibscore::client
