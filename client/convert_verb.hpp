#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "client/clef_search.hpp"

namespace vibscore::client {

struct ConvertRequest {
    std::string in, out;
    std::string from, to;  // format names; empty: from the file names
    // For imports: a clef file, or a registry clef's name found by the clef rule of ClefSearch.
    std::string clef = "lra-phone";
    int track = 0;      // MIDI: which track, from 1; 0 for the first with notes
    bool loop = false;  // Android: repeat the pattern
};

// vibscore convert IN OUT: a score into AHAP, Android JSON or XML, or MIDI; or AHAP, Android,
// RTTTL or MIDI into a score on a clef (with a copy of the clef at the piece's own tempo when
// that differs, written beside the score). Scores and a clef named by registry name are found
// by `clefs`, as check finds them; the imported score names its clef so that check finds it
// again (the registry name, or the clef file's path relative to the score). Returns an exit
// code.
int convert(const ConvertRequest& request, const ClefSearch& clefs, std::ostream& out,
            std::ostream& err);

}  // namespace vibscore::client
