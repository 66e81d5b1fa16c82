#pragma once

#include "client/editor/request.hpp"

namespace vibscore::editor {

class EditorModel;

// What the session around the model does for the actions that are no editing functions: open a
// menu or a list, or ask the world for something (save, open, quit). The button scheme is the
// session; the action table (actions.cpp) names these, so it needs no more of the scheme than
// this and the scheme's file stays above the table it looks actions up in.
class SessionActions {
  public:
    virtual Request choose_clef(EditorModel& model) = 0;
    virtual Request edit_clefs(EditorModel& model) = 0;
    virtual Request save(EditorModel& model) = 0;
    virtual Request save_as(EditorModel& model) = 0;
    virtual Request use_for_event(EditorModel& model) = 0;
    virtual Request open(EditorModel& model) = 0;
    virtual Request tap_rhythm(EditorModel& model) = 0;
    virtual Request quit(EditorModel& model) = 0;

    // No state of its own: sessions compare by what the scheme holds.
    bool operator==(const SessionActions&) const = default;

  protected:
    // Never owned through this interface (the scheme is copied by value): no virtual
    // destructor needed, and none can be deleted through it.
    SessionActions() = default;
    SessionActions(const SessionActions&) = default;
    SessionActions(SessionActions&&) = default;
    SessionActions& operator=(const SessionActions&) = default;
    SessionActions& operator=(SessionActions&&) = default;
    ~SessionActions() = default;
};

}  // namespace vibscore::editor
