#pragma once

#include <optional>
#include <ostream>
#include <string>

namespace vibscore::client {

struct ConvertRequest {
    std::string in, out;
    std::string from, to;            // format names; empty: from the file names
    std::string clef = "lra-phone";  // for imports: a clef file, or a shipped clef's name
    int track = 0;                   // MIDI: which track, from 1; 0 for the first with notes
    bool loop = false;               // Android: repeat the pattern
};

// vibscore convert IN OUT: a score into AHAP, Android JSON or XML, or MIDI; or AHAP, Android,
// RTTTL or MIDI into a score on a clef (with a copy of the clef at the piece's own tempo when
// that differs, written beside the score). Returns an exit code.
int convert(const ConvertRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vibscore::client
