#pragma once

#include <cairo.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>

// Pictures drawn with cairo and written as SVG or PNG, the format told by the file's extension.
namespace vibscore::pictures {

enum class PictureFormat { svg, png };

// .svg or .png; throws std::invalid_argument naming the file otherwise.
PictureFormat picture_format_for(const std::filesystem::path& path);

// The kinds of mark a drawing is made of, one bit each, as each drawing numbers them
// (StaffPicture::Layer, SignalPicture::Layer). Tests draw one kind at a time: to find two kinds
// of ink in one place, and to compare text, which each cairo version rasterises a little
// differently, apart from lines and shapes, which they draw alike.
using Layers = std::uint32_t;
constexpr Layers all_layers = ~Layers{0};

// A drawing of a known size in pixels (SVG points), painted on a white background.
class Drawing {
  public:
    virtual ~Drawing() = default;
    virtual double width() const = 0;
    virtual double height() const = 0;
    // Draws the marks of `layers` only; a picture is all of them.
    virtual void draw(cairo_t* cairo, Layers layers) const = 0;
    // The layers that hold text.
    virtual Layers text_layers() const = 0;
};

// Writes the drawing to `path` in the format its extension names. The file appears complete or
// not at all. Throws std::runtime_error naming the file when cairo or the disk fail.
void write_picture(const Drawing& drawing, const std::filesystem::path& path);

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using CairoPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

enum class Background { white, none };

// The widest and tallest image cairo makes: a PNG of a longer score is refused, naming its size.
constexpr int kMaxImageSide = 32767;

// The drawing on an image surface in memory (ARGB32), for tests and PNG output. Tests draw
// single layers on no background, where a pixel's alpha is how much ink it holds (white text
// is ink too).
SurfacePtr render_image(const Drawing& drawing, Layers layers = all_layers,
                        Background background = Background::white);

}  // namespace vibscore::pictures
