#pragma once

#include <cstddef>
#include <string>

namespace vibscore::editor {

// What the editor asks of the world around the model after a key or button.
struct Request {
    enum class Kind {
        none,
        play,
        stop,
        save,
        save_as,
        open,
        new_score,
        quit,
        save_and_quit,
        keep_event,    // "keep as it was": give `event` back the score `name` ("" the theme's)
        hear_clef,     // play string `string` at number `number` through the clef `document`
        save_clef,     // store the clef `document` as `name` and use it for the cursor's bar
        store_clef,    // store the clef `document` as `name`: bars already use it (a tempo clef)
        assign_event,  // the score as saved plays for `event` from now on (no save, no copy)
    };
    Kind kind = Kind::none;
    std::string name;        // open: the registry name or file; save_as: the name to save under
    std::size_t bar = 0;     // play: the first bar
    bool then_quit = false;  // save_as: quit once saved
    std::string event;       // save, save_as: once saved, `event` plays it ("use for ...")
    std::string document;    // hear_clef, save_clef, store_clef: the clef as a VibClef document
    int string = 0;          // hear_clef
    int number = 0;
    bool operator==(const Request&) const = default;
};

}  // namespace vibscore::editor
