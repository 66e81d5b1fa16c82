#pragma once

#include <optional>
#include <string>
#include <vector>

#include "actuator/declaration.hpp"
#include "client/pictures/picture_file.hpp"
#include "score/clef.hpp"

namespace vibscore::pictures {

// A clef as the thesis' waveform windows show it (Fig. 4.1c, 4.2), with a table of its values:
// - sine: strength over frequency, each string a vertical line at its frequency, each number a
//   horizontal line at its strength, and a dot where they cross: every note the clef can play;
// - curve and line: each string's waveform over one quarter note with its control points,
//   string 6 on top as on the staff; the numbers scale it.
// With an actuator (`show CLEF --actuator`), captioned with its declaration: behind a sine clef's
// strings an LRA's response, the strength full drive gives at each frequency, and at each string
// the strength each number reaches there, a mark drawn over the dots (which become rings) so
// that it shows where it meets one; an ERM is said to have no pitch.
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
        response = 1u << 8,  // the LRA's strength at full drive over frequency
        reached = 1u << 9,   // the strength each number reaches on each string
        caption = 1u << 10,  // the actuator, and for an ERM that it has no pitch
    };

    // The mark of what a number reaches on a string, for tests to find it over the dots.
    static constexpr double reached_ink[3] = {0.85, 0.3, 0.05};

    // `name`: what the title calls the clef (its registry name or file); `actuator`: the one
    // whose response is drawn behind the clef.
    ClefPicture(const Clef& clef, std::string name,
                std::optional<actuator::Declaration> actuator = std::nullopt);

    double width() const override { return width_; }
    double height() const override { return height_; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override { return title | axis_labels | table | caption; }

    // A plot inside the picture: its frame, and what its axes span.
    struct Plot {
        double left = 0.0, top = 0.0, width = 0.0, height = 0.0;
        double x_from = 0.0, x_to = 1.0;  // Hz (sine) or seconds (shapes)
        double y_from = 0.0, y_to = 1.0;  // strength (sine) or level (shapes)

        double x_of(double x) const { return left + (x - x_from) / (x_to - x_from) * width; }
        double y_of(double y) const {
            return top + height - (y - y_from) / (y_to - y_from) * height;
        }
    };
    // One plot for a sine clef; one per string for a shape clef, string 1's first.
    const std::vector<Plot>& plots() const { return plots_; }

    // With an actuator, from its model (actuator::Physics, as clef fit and check use it): the
    // strength full drive gives at this frequency, and the strength number `n` reaches on string
    // `s` with the drive the renderer gives it (compensation on: up to full drive; off: number x
    // rated-drive).
    double full_drive_strength(double frequency_hz) const;
    double reached_strength(std::size_t s, std::size_t n) const;

  private:
    void draw_sine(cairo_t* cairo, Layers layers) const;
    void draw_shapes(cairo_t* cairo, Layers layers) const;
    void draw_frame(cairo_t* cairo, const Plot& plot, Layers layers, bool x_labels,
                    const char* x_title) const;
    void draw_table(cairo_t* cairo, Layers layers) const;
    void draw_response(cairo_t* cairo, Layers layers) const;
    void draw_reached(cairo_t* cairo, Layers layers) const;
    void draw_caption(cairo_t* cairo, Layers layers) const;

    const Clef& clef_;
    std::optional<actuator::Declaration> actuator_;
    std::string title_;
    std::vector<std::string> caption_;
    double caption_top_ = 0.0;
    std::vector<Plot> plots_;
    double table_left_ = 0.0;
    double width_ = 0.0, height_ = 0.0;
};

}  // namespace vibscore::pictures
