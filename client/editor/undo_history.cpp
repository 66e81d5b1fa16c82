#include "client/editor/undo_history.hpp"

#include <vector>

namespace vibscore::editor {

UndoHistory::Stack UndoHistory::push(Stack stack, Snapshot snapshot) {
    const std::size_t depth = stack ? stack->depth + 1 : 1;
    return std::make_shared<const Entry>(Entry{std::move(snapshot), std::move(stack), depth});
}

UndoHistory::Stack UndoHistory::without_bottom(const Stack& stack) {
    std::vector<Snapshot> kept;
    for (const Entry* entry = stack.get(); entry != nullptr && entry->below != nullptr;
         entry = entry->below.get()) {
        kept.push_back(entry->snapshot);
    }
    Stack rebuilt;
    for (auto it = kept.rbegin(); it != kept.rend(); ++it) {
        rebuilt = push(std::move(rebuilt), *it);
    }
    return rebuilt;
}

bool UndoHistory::same(const Entry* a, const Entry* b) {
    for (; a != b; a = a->below.get(), b = b->below.get()) {
        if (a == nullptr || b == nullptr || a->depth != b->depth || !(a->snapshot == b->snapshot)) {
            return false;
        }
    }
    return true;
}

bool UndoHistory::operator==(const UndoHistory& other) const {
    return limit_ == other.limit_ && same(undo_.get(), other.undo_.get()) &&
           same(redo_.get(), other.redo_.get());
}

void UndoHistory::record(Snapshot before) {
    undo_ = push(std::move(undo_), std::move(before));
    if (undo_->depth > limit_) {
        undo_ = without_bottom(undo_);
    }
    redo_.reset();
}

void UndoHistory::drop_last() {
    if (undo_) {
        undo_ = undo_->below;
    }
}

std::optional<Snapshot> UndoHistory::undo(Snapshot current) {
    if (!undo_) {
        return std::nullopt;
    }
    Snapshot previous = undo_->snapshot;
    undo_ = undo_->below;
    redo_ = push(std::move(redo_), std::move(current));
    return previous;
}

std::optional<Snapshot> UndoHistory::redo(Snapshot current) {
    if (!redo_) {
        return std::nullopt;
    }
    Snapshot next = redo_->snapshot;
    redo_ = redo_->below;
    undo_ = push(std::move(undo_), std::move(current));
    return next;
}

}  // namespace vibscore::editor
