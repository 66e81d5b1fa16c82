#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace vibscore::editor {

// An immutable value shared between copies of an editor (the score, the clefs on offer), so a
// copy costs a pointer; compared by value, so editors that hold equal values are equal however
// they came by them.
template <typename T>
class Shared {
  public:
    Shared() : value_(std::make_shared<const T>()) {}
    Shared(T value) : value_(std::make_shared<const T>(std::move(value))) {}  // NOLINT: a value
    template <typename U>
    Shared(std::shared_ptr<U> value) : value_(std::move(value)) {}  // NOLINT: shares it

    const T& operator*() const { return *value_; }
    const T* operator->() const { return value_.get(); }
    // Another copy to change: the shared one stays as it was.
    std::shared_ptr<T> copy() const { return std::make_shared<T>(*value_); }

    bool operator==(const Shared& other) const {
        return value_ == other.value_ || *value_ == *other.value_;
    }

  private:
    std::shared_ptr<const T> value_;
};

}  // namespace vibscore::editor
