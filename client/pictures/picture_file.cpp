#include "client/pictures/picture_file.hpp"

#include <cairo-svg.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace vibscore::pictures {

namespace {

void check(cairo_status_t status, const std::filesystem::path& path) {
    if (status != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(path.string() + ": " + cairo_status_to_string(status));
    }
}

void paint(const Drawing& drawing, cairo_surface_t* surface, Layers layers, Background background) {
    const CairoPtr cairo(cairo_create(surface), &cairo_destroy);
    if (background == Background::white) {
        cairo_set_source_rgb(cairo.get(), 1, 1, 1);
        cairo_paint(cairo.get());
    }
    drawing.draw(cairo.get(), layers);
    cairo_surface_flush(surface);
}

}  // namespace

PictureFormat picture_format_for(const std::filesystem::path& path) {
    const auto extension = path.extension().string();
    if (extension == ".svg") {
        return PictureFormat::svg;
    }
    if (extension == ".png") {
        return PictureFormat::png;
    }
    throw std::invalid_argument("cannot tell the picture format of \"" + path.string() +
                                "\": name it .svg or .png");
}

SurfacePtr render_image(const Drawing& drawing, Layers layers, Background background) {
    const double width = std::ceil(drawing.width()), height = std::ceil(drawing.height());
    if (width > kMaxImageSide || height > kMaxImageSide) {
        // cairo would only say "invalid value (typically too big)"; say which side and what to do.
        throw std::runtime_error("the picture is " + std::to_string(static_cast<long long>(width)) +
                                 "x" + std::to_string(static_cast<long long>(height)) +
                                 " pixels, and an image is at most " +
                                 std::to_string(kMaxImageSide) +
                                 " on a side: draw it as an SVG (--svg), which has no such limit");
    }
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, static_cast<int>(width),
                                                  static_cast<int>(height)),
                       &cairo_surface_destroy);
    check(cairo_surface_status(surface.get()), "picture");
    paint(drawing, surface.get(), layers, background);
    return surface;
}

void write_picture(const Drawing& drawing, const std::filesystem::path& path) {
    const auto format = picture_format_for(path);
    auto temporary = path;
    temporary += ".partial";
    try {
        if (format == PictureFormat::svg) {
            SurfacePtr surface(
                cairo_svg_surface_create(temporary.c_str(), drawing.width(), drawing.height()),
                &cairo_surface_destroy);
            check(cairo_surface_status(surface.get()), path);
            cairo_svg_surface_restrict_to_version(surface.get(), CAIRO_SVG_VERSION_1_1);
            paint(drawing, surface.get(), all_layers, Background::white);
            cairo_surface_finish(surface.get());
            check(cairo_surface_status(surface.get()), path);
        } else {
            const auto surface = render_image(drawing);
            check(cairo_surface_write_to_png(surface.get(), temporary.c_str()), path);
        }
        std::filesystem::rename(temporary, path);
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

}  // namespace vibscore::pictures
