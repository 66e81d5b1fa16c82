#include "score/clef.hpp"

namespace vibscore {

std::string_view to_string(ClefType type) {
    switch (type) {
        case ClefType::curve:
            return "curve";
        case ClefType::line:
            return "line";
        case ClefType::sine:
            break;
    }
    return "sine";
}

}  // namespace vibscore
