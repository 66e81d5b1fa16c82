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
// bar a clef box with the bar's clef and beat count ("4 beats"), cyan below four beats, white at
// four, magenta above. Columns come from the editor's staff layout, so the picture and
// `vibscore show` agree; a long score breaks into systems at bar lines.
//
// Each system stacks its marks in rows that never share a pixel: the clef boxes, then the
// hairpins, then room for the stems of notes on string 6, the six strings, and the ties below.
class StaffPicture : public Drawing {
  public:
    struct Options {
        int columns_per_system = 110;
    };

    // The kinds of mark, one layer each (see Drawing).
    enum Layer : Layers {
        title = 1u << 0,
        staff_lines = 1u << 1,
        bar_lines = 1u << 2,
        clef_boxes = 1u << 3,
        clef_labels = 1u << 4,
        heads = 1u << 5,  // note heads and their dots
        numbers = 1u << 6,
        stems = 1u << 7,  // stems and flags
        rests = 1u << 8,
        hairpins = 1u << 9,
        ties = 1u << 10,  // legato arcs and portamento lines
    };

    explicit StaffPicture(const Score& score) : StaffPicture(score, Options{}) {}
    StaffPicture(const Score& score, const Options& options);

    double width() const override { return width_; }
    double height() const override { return height_; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override { return title | clef_labels | numbers; }

    struct Point {
        double x = 0.0, y = 0.0;
    };
    // Where each note's head is drawn, in playing order.
    std::vector<Point> head_centres() const;

    // Each bar's clef box as drawn: its corner, size and label.
    struct ClefBox {
        std::size_t bar = 0;
        double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
        std::string label;  // "shaker  4 beats", or "shaker  4" where a bar is too narrow
    };
    const std::vector<ClefBox>& clef_boxes_drawn() const { return clef_boxes_; }

    // The colour note heads are outlined with, and nothing else is: tests count heads by it.
    static constexpr double head_ink[3] = {0.08, 0.08, 0.25};

  private:
    struct System {
        int begin = 0, end = 0;  // layout columns
        double top = 0.0;        // y of its clef-box row
        // The layout's spans in its columns: [first_span, end_span), spans being in column order.
        std::size_t first_span = 0, end_span = 0;
    };
    // A hairpin: a run of notes with the same dynamics; a legato arc or a portamento line from one
    // note to the next. Found once, in score order (so in column order), and drawn by each system
    // they reach: a long score is drawn in n log n, not systems x notes.
    struct Hairpin {
        const editor::Span* from = nullptr;
        const editor::Span* to = nullptr;
        Dynamics dynamics = Dynamics::none;
    };
    struct Tie {
        int from = 0, to = 0;  // the two heads' columns
        const Note* note = nullptr;
        const Note* next = nullptr;
    };

    std::string title_text() const;
    double column_x(const System& system, double column) const;
    double head_x(const System& system, int column) const;
    double string_y(const System& system, int string) const;
    void place_clef_boxes(cairo_t* cairo);
    void find_hairpins();
    void find_ties();
    void draw_system(cairo_t* cairo, const System& system, Layers layers) const;
    void draw_note(cairo_t* cairo, const System& system, const editor::Span& span, const Note& note,
                   Layers layers) const;
    void draw_rest(cairo_t* cairo, const System& system, const editor::Span& span,
                   const Rest& rest) const;
    void draw_clef_box(cairo_t* cairo, const ClefBox& box, Layers layers) const;
    void draw_hairpins(cairo_t* cairo, const System& system) const;
    void draw_ties(cairo_t* cairo, const System& system) const;

    const Score& score_;
    editor::StaffLayout layout_;
    std::vector<System> systems_;
    std::vector<Hairpin> hairpins_;
    std::vector<Tie> ties_;
    std::vector<ClefBox> clef_boxes_;
    double width_ = 0.0, height_ = 0.0;
};

}  // namespace vibscore::pictures
