#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "client/editor/buttons.hpp"

namespace vibscore::editor {

// A name typed with the six buttons: what save-as stores a score under. It opens on a name
// already (a free one is proposed), so keeping it is one Select.
//   Up/Down     the character under the cursor steps through a-z, 0-9, '-', '.', '_' (wrapping)
//   Left/Right  the cursor; Right past the last character adds one
//   Select      done: save under this name
//   Back        the other choices: Down deletes the character, Up inserts one, Select or Left
//               or Right go back to typing, Back cancels
// Registry names are 1 to 64 of those characters, starting with a letter or digit
// (docs/daemon.md); a name that is not one cannot be chosen, and says why.
class NameEntry {
  public:
    enum class Outcome { typing, done, cancelled };

    void start(std::string name);
    Outcome press(Button button);

    const std::string& name() const { return name_; }
    std::size_t cursor() const { return cursor_; }
    bool more() const { return more_; }
    // Why the name cannot be chosen, or "" when it can.
    std::string problem() const;
    // What the buttons do now (fits 40 columns).
    std::string hint() const;
    // The name with the character under the cursor in brackets: "ringtone-[2]".
    std::string shown() const;

    bool operator==(const NameEntry&) const = default;

  private:
    std::string name_;
    std::size_t cursor_ = 0;
    bool more_ = false;
};

// Whether `name` is a registry name: 1 to 64 of a-z 0-9 . _ -, starting with a letter or digit.
bool is_registry_name(const std::string& name);

// A registry name none of `taken` holds, made from `name`: "ringtone" gives "ringtone-2",
// "ringtone-2" gives "ringtone-3" (or the next one free); a name that cannot be one gives
// "tacton-2".
std::string free_name(const std::string& name, const std::vector<std::string>& taken);

}  // namespace vibscore::editor
