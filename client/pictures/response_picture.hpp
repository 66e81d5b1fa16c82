#pragma once

#include <string>
#include <vector>

#include "client/pictures/picture_file.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::pictures {

// What a declared actuator makes of a score (`vibscore render --actuator --png`): the strength
// written, and the strength the actuator produces from the renderer's drives without and with
// compensation, over the score and the ringing after it. Strength is in the declaration's units
// (1 = the rated drive). The caption names the actuator (actuator::describe()) and, on lines of
// its own after a '\n', the clefs the score was played through; the legend names every line,
// the dashed ones too (where bars begin, where the score ends); along the top, each bar's number
// and, where it changes, its clef.
class ResponsePicture : public Drawing {
  public:
    struct Options {
        double width = 960.0;
        double height = 400.0;
        // The clef each bar plays through, by name, in bar order: drawn along the top where it
        // changes. Empty: bar numbers only.
        std::vector<std::string> bar_clefs;
    };

    ResponsePicture(const render::Performance& performance, render::ActuatorResponse response,
                    std::string title, std::string caption)
        : ResponsePicture(performance, std::move(response), std::move(title), std::move(caption),
                          Options{}) {}
    ResponsePicture(const render::Performance& performance, render::ActuatorResponse response,
                    std::string title, std::string caption, const Options& options);

    // The kinds of mark, one layer each (see Drawing).
    enum Layer : Layers {
        title = 1u << 0,
        caption = 1u << 1,      // the actuator
        legend = 1u << 2,       // the legend's line samples
        bar_labels = 1u << 10,  // bar numbers and clef names along the top
        legend_text = 1u << 3,
        frame = 1u << 4,  // the plot's frame and the ticks on its axes
        axis_labels = 1u << 5,
        bar_boundaries = 1u << 6,  // where bars begin and the score ends
        written = 1u << 7,
        uncompensated = 1u << 8,
        compensated = 1u << 9,
    };

    // The traces' colours (red, green, blue in 0..1), for tests to tell them apart.
    static constexpr double written_ink[3] = {0.35, 0.35, 0.35};
    static constexpr double uncompensated_ink[3] = {0.9, 0.45, 0.0};
    static constexpr double compensated_ink[3] = {0.1, 0.3, 0.8};
    // The dashed lines where a bar begins and where the score ends.
    static constexpr double bar_line_ink[3] = {0.7, 0.7, 0.7};
    static constexpr double end_line_ink[3] = {0.3, 0.3, 0.3};

    double width() const override { return options_.width; }
    double height() const override { return options_.height; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override {
        return title | caption | legend_text | axis_labels | bar_labels;
    }

    // Where time t and strength s are drawn.
    double x_of(double t) const;
    double y_of(double strength) const;
    // The strength at the top of the plot.
    double top() const { return top_; }
    // How long the picture shows: the score and the ringing after it.
    double span() const { return span_; }

  private:
    void draw_header(cairo_t* cairo, Layers layers) const;
    void draw_bar_labels(cairo_t* cairo, Layers layers) const;
    double plot_top() const;
    void draw_axes(cairo_t* cairo, Layers layers) const;
    void draw_boundaries(cairo_t* cairo, Layers layers) const;
    void draw_traces(cairo_t* cairo, Layers layers) const;

    const render::Performance& performance_;
    render::ActuatorResponse response_;
    std::string title_;
    std::vector<std::string> caption_;  // its lines
    Options options_;
    double top_ = 1.0;
    double span_ = 1.0;
};

}  // namespace vibscore::pictures
