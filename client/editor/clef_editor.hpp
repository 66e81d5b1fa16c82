#pragma once

#include <string>
#include <vector>

#include "client/editor/buttons.hpp"
#include "score/clef.hpp"

namespace vibscore::editor {

// Editing one clef with the six buttons, as the thesis' editor has a window per clef (§4.2,
// Fig. 4.1b/c, 4.2): for a sine clef each string's frequency and each number's amplitude, and
// the tempo; for a curve or line clef, each string's waveform by its control points.
//
//   fields   Up/Down: the tempo, strings 6..1, numbers 1..9 (wrapping)
//            Right/Left: the value one step up/down (Hz, amplitude, seconds; Back, Up: fine)
//            Select: hear it (the string at the number under the cursor) or, on a curve or
//            line string, its points
//            Back: Up fine/coarse, Down hear, Select save as (and use for the bar),
//            Back close
//   points   Up/Down: the point's level, Right/Left: its time, Select: the next point
//            Back: Up add a point after it, Down delete it, Left the point before,
//            Right fine/coarse, Select back to the points, Back back to the fields
// Every change asks to be heard: what the thumb changes, the actuator plays at once.
class ClefEditor {
  public:
    enum class Outcome {
        editing,
        hear,     // play the string at the number under the cursor, as the clef is now
        save_as,  // store it under a new name and use it for the bar
        close,
    };
    enum class Level { fields, fields_more, points, points_more };

    ClefEditor() = default;
    ClefEditor(std::string id, Clef clef);

    Outcome press(Button button);

    const std::string& id() const { return id_; }
    const Clef& clef() const { return clef_; }
    bool modified() const { return clef_ != original_; }
    Level level() const { return level_; }
    bool fine() const { return fine_; }
    // What plays when heard: a string (1-based) at a number (1-based). The string is the one
    // last changed or heard (Select) — moving the cursor past the strings to reach the numbers
    // does not change it — so a number changed is heard on the string just edited; the number
    // is the one under the cursor or last changed.
    int string() const { return string_; }
    int number() const { return number_; }
    // Said after a number's amplitude is set above the next number's (or below the one before):
    // allowed, since a clef may want it, but a stronger number that plays weaker surprises
    // ("n5 0.80 is above n6 0.70"). "" when the numbers rise.
    const std::string& notice() const { return notice_; }
    // The field under the cursor: 0 the tempo, then strings from the highest down, then the
    // numbers from 1.
    int field() const { return field_; }
    int point() const { return point_; }

    // The window: `height` lines of at most `width` columns, the field under the cursor marked
    // '>' (a glyph: no colour needed), the notice (if any) on the last line. `feel`, where the
    // actuator's response is known, is written beside each string (string 1 first).
    std::vector<std::string> lines(int width, int height,
                                   const std::vector<std::string>& feel = {}) const;
    // What the buttons do now (fits 40 columns).
    std::string hint() const;

    bool operator==(const ClefEditor&) const = default;

  private:
    int strings() const { return static_cast<int>(clef_.strings.size()); }
    int numbers() const { return static_cast<int>(clef_.numbers.size()); }
    int fields() const { return 1 + strings() + numbers(); }
    int string_of_field(int field) const;  // 1-based, or 0
    int number_of_field(int field) const;  // 1-based, or 0
    bool waveform() const { return clef_.type != ClefType::sine; }
    Outcome change(int direction);
    Outcome move_point(double dt, double dlevel);
    std::vector<ClefPoint>& points() {
        return clef_.strings[static_cast<std::size_t>(string_ - 1)].points;
    }
    const std::vector<ClefPoint>& points() const {
        return clef_.strings[static_cast<std::size_t>(string_ - 1)].points;
    }

    std::string id_;
    Clef clef_;
    Clef original_;
    Level level_ = Level::fields;
    int field_ = 0;
    int point_ = 0;
    int string_ = 1;
    int number_ = 5;
    bool fine_ = false;
    std::string notice_;
};

// A waveform as a row of block characters, `width` columns over one quarter note, as the clef
// draws it (Catmull-Rom for a curve, straight segments for a line).
std::string sparkline(const Clef& clef, int string, int width);

}  // namespace vibscore::editor
