#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace vibscore::editor {

struct EditOptions {
    std::string target;                // a registry name or a file; empty for a new score
    std::string clef;                  // a new score's clef: a registry clef or a clef file
    std::vector<std::string> buttons;  // evdev devices whose keys are the six buttons
    std::string button_map;            // ButtonMap::parse text; empty for the phone map
    bool grab = false;                 // take the devices' keys for the editor alone
};

// `vibscore edit`: the ncurses editor, until the user quits. Returns an exit code; problems
// that stop it from starting are explained on err.
int run_editor(const EditOptions& options, std::ostream& err);

}  // namespace vibscore::editor
