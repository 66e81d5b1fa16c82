#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "client/editor/buttons.hpp"

namespace vibscore::editor {

// A name typed with the six buttons: what save-as stores a score under. It opens on names
// proposed first (an event's, the score's title, a free "<name>-2"), so keeping one is one
// Select; where a name must be typed, every character is two presses, or three for the rare
// ones, and the first character typed replaces the proposal.
//
//   proposals (two or more)  Up/Down choose, Select saves under it, Right types a new name,
//                            Left types on from the highlighted one, Back cancels
//   letters                  Up/Down/Right/Left: one of four groups of the letters most used in
//                            names (e t a o i | n s h r d | l c u m w | f g y p -), then one
//                            of the group's five with Up/Down/Right/Left/Select; Select saves;
//                            Back: more
//   more                     Up/Down/Right/Left: the other characters (b v k j x | q z . _ 0 |
//                            1 2 3 4 5 | 6 7 8 9), then one of them; Select deletes the last
//                            character; Back: back to the proposals (or cancel with one)
// In a group, Back turns back to the letters. Registry names are 1 to 64 of those characters,
// starting with a letter or digit (docs/daemon.md); a name that is not one cannot be saved
// under, and says why.
class NameEntry {
  public:
    enum class Outcome { typing, done, cancelled };
    enum class Level { proposals, letters, letter_group, more, more_group };

    // `proposals`, best first; at least one (an empty list proposes "tacton-2").
    void start(std::vector<std::string> proposals);
    Outcome press(Button button);
    // A character typed on a keyboard, as if chosen with the buttons: the characters of
    // registry names (a-z, 0-9, '.', '_', '-'; A-Z as lower case). False for any other, which is
    // not taken.
    bool type_key(char c);
    // The name chosen cannot be taken (the caller knows why): typing goes on, the box says it.
    void refuse(std::string why) { refused_ = std::move(why); }

    // The name Select saves under now.
    const std::string& name() const;
    Level level() const { return level_; }
    // The name shown is a proposal not typed into yet: the first character typed replaces it.
    bool untouched() const { return untouched_; }
    // Why the name cannot be saved under, or "" when it can.
    std::string problem() const;
    // What the buttons do now (fits 40 columns).
    std::string hint() const;
    // The box's lines: the proposals to choose from, or the name ("[ringtone-2]" while a
    // proposal is untouched, "my-r|" while typing) and why it cannot be saved under.
    std::vector<std::string> lines() const;
    int highlighted() const { return level_ == Level::proposals ? chosen_ : 0; }

    bool operator==(const NameEntry&) const = default;

  private:
    void type(char c);
    Outcome back_from_more();

    std::vector<std::string> proposals_;
    int chosen_ = 0;
    std::string name_;
    bool untouched_ = true;
    Level level_ = Level::letters;
    int group_ = 0;
    std::string refused_;  // why the last character typed was not taken
};

// Whether `name` is a registry name: 1 to 64 of a-z 0-9 . _ -, starting with a letter or digit.
bool is_registry_name(const std::string& name);

// A registry name none of `taken` holds, made from `name`: "ringtone" gives "ringtone-2",
// "ringtone-2" gives "ringtone-3" (or the next one free); a name that cannot be one gives
// "tacton-2".
std::string free_name(const std::string& name, const std::vector<std::string>& taken);

// A title as a registry name: lower case, every run of other characters one '-' ("My Ring!" ->
// "my-ring"), at most 64 characters; "" when nothing is left.
std::string name_from_title(std::string_view title);

// What save-as proposes, best first, each once and none taken: a free name made from `event`
// (when the score is being made for one: "phone-incoming-call-2"), the score's title as a name,
// and a free name made from the score's own `name`.
std::vector<std::string> name_proposals(const std::string& name, const std::string& title,
                                        const std::string& event,
                                        const std::vector<std::string>& taken);

}  // namespace vibscore::editor
