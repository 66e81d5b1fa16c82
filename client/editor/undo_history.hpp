#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include "client/editor/position.hpp"
#include "client/editor/shared_value.hpp"
#include "score/score.hpp"

namespace vibscore::editor {

// What undo brings back: the score and where the cursor stood.
struct Snapshot {
    Shared<Score> score;
    Position cursor;
    int string = 1;
    bool operator==(const Snapshot&) const = default;
};

// Undo and redo stacks of snapshots, the oldest dropped beyond `limit` steps. The stacks are
// shared lists and snapshots share their scores, so copying a history (the press planner
// copies whole editors by the million) costs two pointers.
class UndoHistory {
  public:
    explicit UndoHistory(std::size_t limit = 500) : limit_(limit) {}

    // Records the state before a change; a new change forgets what could be redone.
    void record(Snapshot before);
    // Forgets the last record (a change that turned out to change nothing).
    void drop_last();
    // The state to go back to, given the current one (which redo will bring back).
    std::optional<Snapshot> undo(Snapshot current);
    std::optional<Snapshot> redo(Snapshot current);

    const Snapshot* last() const { return undo_ ? &undo_->snapshot : nullptr; }

    // Equal when both stacks hold equal snapshots (shared parts are not compared again).
    bool operator==(const UndoHistory& other) const;

  private:
    struct Entry {
        Snapshot snapshot;
        std::shared_ptr<const Entry> below;
        std::size_t depth;
    };
    static bool same(const Entry* a, const Entry* b);
    using Stack = std::shared_ptr<const Entry>;
    static Stack push(Stack stack, Snapshot snapshot);
    static Stack without_bottom(const Stack& stack);

    std::size_t limit_;
    Stack undo_;
    Stack redo_;
};

}  // namespace vibscore::editor
