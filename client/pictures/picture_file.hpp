#pragma once

#include <cairo.h>

#include <filesystem>
#include <functional>
#include <memory>

// Pictures drawn with cairo and written as SVG or PNG, the format told by the file's extension.
namespace vibscore::pictures {

enum class PictureFormat { svg, png };

// .svg or .png; throws std::invalid_argument naming the file otherwise.
PictureFormat picture_format_for(const std::filesystem::path& path);

// A drawing of a known size in pixels (SVG points), painted on a white background.
class Drawing {
  public:
    virtual ~Drawing() = default;
    virtual double width() const = 0;
    virtual double height() const = 0;
    virtual void draw(cairo_t* cairo) const = 0;
};

// Writes the drawing to `path` in the format its extension names. The file appears complete or
// not at all. Throws std::runtime_error naming the file when cairo or the disk fail.
void write_picture(const Drawing& drawing, const std::filesystem::path& path);

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using CairoPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// The drawing on an image surface in memory (ARGB32), for tests and PNG output.
SurfacePtr render_image(const Drawing& drawing);

}  // namespace vibscore::pictures
