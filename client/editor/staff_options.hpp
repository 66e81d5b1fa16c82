#pragma once

#include <optional>

#include "client/editor/button_scheme.hpp"
#include "client/editor/editor_model.hpp"
#include "client/editor/staff_layout.hpp"

namespace vibscore::editor {

// What the editor's staff marks for the state it is in: the cursor, the block, the playback
// cursor, and while entering what is open at the cursor. Only a proposal (a symbol not yet in
// the score) is left out of its bar's beat count: a symbol being changed is still the score's,
// so its bar counts it (a bar box read `[lra-phone-2 2.5]` for a bar of three beats).
LayoutOptions staff_options(const EditorModel& model, const ButtonScheme& scheme,
                            std::optional<Position> playing);

}  // namespace vibscore::editor
