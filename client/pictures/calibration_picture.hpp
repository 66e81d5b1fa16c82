#pragma once

#include <string>
#include <vector>

#include "actuator/calibration.hpp"
#include "client/pictures/picture_file.hpp"

namespace vibscore::pictures {

// What `vibscore calibrate --png/--svg` draws, so a person sees whether to trust an estimate: the
// vibration the accelerometer recorded during the probe (its magnitude, gravity taken out), and
// over it what the model predicts for the same probe with the fitted numbers (solid) and with the
// declared ones (dashed), in m/s² over time. The caption says the numbers and the verdict.
class CalibrationPicture : public Drawing {
  public:
    struct Options {
        double width = 960.0;
        double height = 340.0;
    };

    // The three traces; `declared` may be empty (nothing declared) and `fitted` too (nothing
    // could be fitted). Every trace's times are seconds from the probe's start.
    struct Traces {
        actuator::calibration::Trace recorded;
        actuator::calibration::Trace fitted;
        actuator::calibration::Trace declared;
    };

    CalibrationPicture(Traces traces, std::string title, std::string caption)
        : CalibrationPicture(std::move(traces), std::move(title), std::move(caption), Options{}) {}
    CalibrationPicture(Traces traces, std::string title, std::string caption,
                       const Options& options);

    enum Layer : Layers {
        title = 1u << 0,
        caption = 1u << 1,
        legend = 1u << 2,
        legend_text = 1u << 3,
        frame = 1u << 4,
        axis_labels = 1u << 5,
        recorded = 1u << 6,
        fitted = 1u << 7,
        declared = 1u << 8,
    };

    static constexpr double recorded_ink[3] = {0.55, 0.55, 0.55};
    static constexpr double fitted_ink[3] = {0.1, 0.3, 0.8};
    static constexpr double declared_ink[3] = {0.9, 0.45, 0.0};

    double width() const override { return options_.width; }
    double height() const override { return options_.height; }
    void draw(cairo_t* cairo, Layers layers) const override;
    Layers text_layers() const override { return title | caption | legend_text | axis_labels; }

    double x_of(double t) const;
    double y_of(double accel) const;

  private:
    void draw_header(cairo_t* cairo, Layers layers) const;
    void draw_axes(cairo_t* cairo, Layers layers) const;
    void draw_traces(cairo_t* cairo, Layers layers) const;

    Traces traces_;
    std::string title_;
    std::string caption_;
    Options options_;
    double top_ = 1.0;
    double span_ = 1.0;
};

}  // namespace vibscore::pictures
