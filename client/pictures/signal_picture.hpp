#pragma once

#include <string>
#include <vector>

#include "client/pictures/picture_file.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::pictures {

// The drive signal over time with its envelope, like thesis Fig. 2.3c: y(t) in clef units,
// the envelope as ±strength, dashed lines where bars begin (numbered above the plot, where no
// signal reaches), thin ones where notes and rests begin, and ticks on the time axis.
class SignalPicture : public Drawing {
  public:
    struct Options {
        double width = 960.0;
        double height = 320.0;
    };

    SignalPicture(const render::Performance& performance, std::string title)
        : SignalPicture(performance, std::move(title), Options{}) {}
    SignalPicture(const render::Performance& performance, std::string title,
                  const Options& options);

    // The kinds of mark, one layer each (see Drawing).
    enum Layer : Layers {
        title = 1u << 0,
        legend = 1u << 1,  // the legend's line samples
        legend_text = 1u << 2,
        frame = 1u << 3,  // the plot's frame and the ticks on its time axis
        axis_labels = 1u << 4,
        bar_boundaries = 1u << 5,
        bar_labels = 1u << 6,
        note_boundaries = 1u << 7,
        signal = 1u << 8,
        envelope = 1u << 9,
    };

    double width() const override { return options_.width; }
    double height() const override { return options_.height; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override { return title | legend_text | axis_labels | bar_labels; }

    // Where time t and level y are drawn.
    double x_of(double t) const;
    double y_of(double y) const;

  private:
    void draw_title_and_legend(cairo_t* cairo, Layers layers) const;
    void draw_axes(cairo_t* cairo, Layers layers) const;
    void draw_boundaries(cairo_t* cairo, Layers layers) const;
    void draw_signal(cairo_t* cairo, Layers layers) const;

    const render::Performance& performance_;
    std::string title_;
    Options options_;
    double peak_ = 1.0;
    double rate_ = 1.0;              // samples per second drawn
    std::vector<double> samples_;    // the signal
    std::vector<double> strengths_;  // its envelope
};

}  // namespace vibscore::pictures
