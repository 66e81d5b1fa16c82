#pragma once

#include <cairo.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "client/pictures/picture_file.hpp"

// Looking at pictures in tests: where each kind of ink is, where two kinds meet, and whether a
// picture shows what a golden one does. Text is judged apart from lines and shapes: every cairo
// version draws a line alike, but each rasterises text a little differently (cairo 1.18 places
// glyphs at quarter pixels and draws them lighter than 1.16).
namespace vibscore::testing {

struct Pixel {
    int r = 0, g = 0, b = 0, a = 0;
    bool white() const { return r > 245 && g > 245 && b > 245; }
};

// An ARGB32 image's pixels, copied out of cairo.
class Image {
  public:
    explicit Image(cairo_surface_t* surface);
    static Image read_png(const std::filesystem::path& path);
    static Image of(const pictures::Drawing& drawing,
                    pictures::Layers layers = pictures::all_layers);
    // The ink of `layers` alone on no background: alpha is how much ink a pixel holds.
    static Image ink_of(const pictures::Drawing& drawing, pictures::Layers layers);

    int width() const { return width_; }
    int height() const { return height_; }
    // Outside the image: transparent.
    Pixel at(int x, int y) const;
    void set(int x, int y, Pixel pixel);
    // 0 (black) to 255 (white).
    double luminance(int x, int y) const;

  private:
    Image(int width, int height) : width_(width), height_(height), pixels_(width * height) {}
    int width_ = 0, height_ = 0;
    std::vector<Pixel> pixels_;
};

struct Place {
    int x = 0, y = 0;
};

// Pixels where both images hold at least `threshold` of ink (alpha out of 255).
std::vector<Place> shared_ink(const Image& a, const Image& b, int threshold = 16);

// Compares images of a picture with golden ones. Outside the picture's text (and a pixel around
// it) every pixel must match within a small tolerance; each piece of text must have its ink
// where the golden's is, as much of it and in the same shape, to within how rasterisers differ.
class GoldenCheck {
  public:
    explicit GoldenCheck(const pictures::Drawing& picture);

    // What differs between `golden` and `drawn`, an image of the picture, in words ("" when
    // they show the same).
    std::string differences(const Image& golden, const Image& drawn) const;

  private:
    Image text_ink_;  // the picture's text alone
    Image under_;     // everything but its text, drawn alike by every cairo version
};

}  // namespace vibscore::testing
