#include "client/editor/staff_options.hpp"

namespace vibscore::editor {

LayoutOptions staff_options(const EditorModel& model, const ButtonScheme& scheme,
                            std::optional<Position> playing) {
    LayoutOptions options;
    options.end_positions = true;
    options.cursor = model.cursor();
    options.cursor_string = model.string();
    options.block = model.block();
    options.playing = playing;
    if (scheme.mode() == ButtonScheme::Mode::entry) {
        if (!model.changing()) {
            options.entering = model.cursor();
        }
        // Changing runs on from symbol to symbol: the staff says which kind is open.
        options.cursor_label = model.changing() ? "change" : "new";
    }
    return options;
}

}  // namespace vibscore::editor
