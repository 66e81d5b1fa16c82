#pragma once

#include <string>
#include <vector>

#include "client/editor/staff_layout.hpp"
#include "client/pictures/picture_file.hpp"
#include "score/score.hpp"

namespace vibscore::pictures {

// The staff as thesis Fig. 4.1 draws it: six string lines, bar lines, note heads with their
// number (hollow for half and whole notes, filled for shorter ones, with stems, flags and dots
// telling the lengths apart), rests, hairpins, legato arcs and portamento lines, and over each
// bar a clef box with the bar's beat count, cyan below four beats, white at four, magenta above.
// Columns come from the editor's staff layout, so the picture and `vibscore show` agree; a long
// score breaks into systems at bar lines.
class StaffPicture : public Drawing {
  public:
    struct Options {
        int columns_per_system = 110;
    };

    explicit StaffPicture(const Score& score) : StaffPicture(score, Options{}) {}
    StaffPicture(const Score& score, const Options& options);

    double width() const override { return width_; }
    double height() const override { return height_; }
    void draw(cairo_t* cairo) const override;

    struct Point {
        double x = 0.0, y = 0.0;
    };
    // Where each note's head is drawn, in playing order.
    std::vector<Point> head_centres() const;

    // The colour note heads are outlined with, and nothing else is: tests count heads by it.
    static constexpr double head_ink[3] = {0.08, 0.08, 0.25};

  private:
    struct System {
        int begin = 0, end = 0;  // layout columns
        double top = 0.0;        // y of its clef-box row
    };

    std::string title_text() const;
    double column_x(const System& system, double column) const;
    double string_y(const System& system, int string) const;
    void draw_system(cairo_t* cairo, const System& system) const;
    void draw_note(cairo_t* cairo, const System& system, const editor::Span& span,
                   const Note& note) const;
    void draw_rest(cairo_t* cairo, const System& system, const editor::Span& span,
                   const Rest& rest) const;
    void draw_clef_box(cairo_t* cairo, const System& system, const editor::Span& bar_line) const;
    void draw_hairpins(cairo_t* cairo, const System& system) const;
    void draw_ties(cairo_t* cairo, const System& system) const;

    const Score& score_;
    editor::StaffLayout layout_;
    std::vector<System> systems_;
    double width_ = 0.0, height_ = 0.0;
};

}  // namespace vibscore::pictures
