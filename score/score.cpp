#include "score/score.hpp"

namespace vibscore {

const ClefDeclaration* Score::find_clef(std::string_view id) const {
    for (const auto& clef : clefs) {
        if (clef.id == id) {
            return &clef;
        }
    }
    return nullptr;
}

double Score::beat_count(const Bar& bar) {
    double total = 0.0;
    for (const auto& symbol : bar.symbols) {
        if (const auto* note = std::get_if<Note>(&symbol)) {
            total += beats(note->length);
        } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
            total += beats(rest->length);
        }
    }
    return total;
}

std::string_view to_string(Dynamics dynamics) {
    switch (dynamics) {
        case Dynamics::crescendo:
            return "crescendo";
        case Dynamics::decrescendo:
            return "decrescendo";
        case Dynamics::none:
            break;
    }
    return "none";
}

}  // namespace vibscore
