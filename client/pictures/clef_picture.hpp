#pragma once

#include <string>
#include <vector>

#include "client/pictures/picture_file.hpp"
#include "score/clef.hpp"

namespace vibscore::pictures {

// A clef as the thesis' waveform windows show it (Fig. 4.1c, 4.2), with a table of its values:
// - sine: amplitude over frequency, each string a vertical line at its frequency, each number a
//   horizontal line at its amplitude, and a dot where they cross: every note the clef can play;
// - curve and line: each string's waveform over one quarter note with its control points,
//   string 6 on top as on the staff; the numbers scale it.
class ClefPicture : public Drawing {
  public:
    // The kinds of mark, one layer each (see Drawing).
    enum Layer : Layers {
        title = 1u << 0,
        frames = 1u << 1,  // plot frames, ticks and grid
        axis_labels = 1u << 2,
        strings = 1u << 3,  // a sine string's line, or a shape string's waveform
        numbers = 1u << 4,  // a sine number's line
        notes = 1u << 5,    // where a sine string and number cross
        points = 1u << 6,   // a shape string's control points
        table = 1u << 7,
    };

    // `name`: what the title calls the clef (its registry name or file).
    ClefPicture(const Clef& clef, std::string name);

    double width() const override { return width_; }
    double height() const override { return height_; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override { return title | axis_labels | table; }

    // A plot inside the picture: its frame, and what its axes span.
    struct Plot {
        double left = 0.0, top = 0.0, width = 0.0, height = 0.0;
        double x_from = 0.0, x_to = 1.0;  // Hz (sine) or seconds (shapes)
        double y_from = 0.0, y_to = 1.0;  // amplitude (sine) or level (shapes)

        double x_of(double x) const { return left + (x - x_from) / (x_to - x_from) * width; }
        double y_of(double y) const {
            return top + height - (y - y_from) / (y_to - y_from) * height;
        }
    };
    // One plot for a sine clef; one per string for a shape clef, string 1's first.
    const std::vector<Plot>& plots() const { return plots_; }

  private:
    void draw_sine(cairo_t* cairo, Layers layers) const;
    void draw_shapes(cairo_t* cairo, Layers layers) const;
    void draw_frame(cairo_t* cairo, const Plot& plot, Layers layers, bool x_labels,
                    const char* x_title) const;
    void draw_table(cairo_t* cairo, Layers layers) const;

    const Clef& clef_;
    std::string title_;
    std::vector<Plot> plots_;
    double table_left_ = 0.0;
    double width_ = 0.0, height_ = 0.0;
};

}  // namespace vibscore::pictures
