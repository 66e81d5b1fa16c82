#pragma once

#include <string>

#include "client/pictures/picture_file.hpp"
#include "daemon/render/performance.hpp"

namespace vibscore::pictures {

// The drive signal over time with its envelope, like thesis Fig. 2.3c: y(t) in clef units,
// the envelope as ±strength, dashed lines where bars begin, thin ones where notes and rests
// begin, and ticks on the time axis.
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

    double width() const override { return options_.width; }
    double height() const override { return options_.height; }
    void draw(cairo_t* cairo) const override;

    // Where time t and level y are drawn.
    double x_of(double t) const;
    double y_of(double y) const;

  private:
    void draw_axes(cairo_t* cairo) const;
    void draw_boundaries(cairo_t* cairo) const;
    void draw_signal(cairo_t* cairo) const;

    const render::Performance& performance_;
    std::string title_;
    Options options_;
    double peak_ = 1.0;
};

}  // namespace vibscore::pictures
