#include "tests/unit/picture_ink.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace vibscore::testing {

Image::Image(cairo_surface_t* surface)
    : Image(cairo_image_surface_get_width(surface), cairo_image_surface_get_height(surface)) {
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS ||
        cairo_image_surface_get_format(surface) != CAIRO_FORMAT_ARGB32) {
        throw std::runtime_error("not an ARGB32 image");
    }
    cairo_surface_flush(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    for (int y = 0; y < height_; ++y) {
        const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * stride);
        for (int x = 0; x < width_; ++x) {
            const std::uint32_t value = row[x];
            pixels_[y * width_ + x] = {
                static_cast<int>(value >> 16 & 0xFF), static_cast<int>(value >> 8 & 0xFF),
                static_cast<int>(value & 0xFF), static_cast<int>(value >> 24 & 0xFF)};
        }
    }
}

Image Image::read_png(const std::filesystem::path& path) {
    const pictures::SurfacePtr surface(cairo_image_surface_create_from_png(path.c_str()),
                                       &cairo_surface_destroy);
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        throw std::runtime_error(path.string() + ": " +
                                 cairo_status_to_string(cairo_surface_status(surface.get())));
    }
    if (cairo_image_surface_get_format(surface.get()) == CAIRO_FORMAT_ARGB32) {
        return Image(surface.get());
    }
    // An opaque PNG reads as RGB24: paint it onto ARGB32.
    const pictures::SurfacePtr argb(
        cairo_image_surface_create(CAIRO_FORMAT_ARGB32,
                                   cairo_image_surface_get_width(surface.get()),
                                   cairo_image_surface_get_height(surface.get())),
        &cairo_surface_destroy);
    const pictures::CairoPtr cairo(cairo_create(argb.get()), &cairo_destroy);
    cairo_set_source_surface(cairo.get(), surface.get(), 0, 0);
    cairo_paint(cairo.get());
    return Image(argb.get());
}

Image Image::of(const pictures::Drawing& drawing, pictures::Layers layers) {
    return Image(pictures::render_image(drawing, layers).get());
}

Image Image::ink_of(const pictures::Drawing& drawing, pictures::Layers layers) {
    return Image(pictures::render_image(drawing, layers, pictures::Background::none).get());
}

Pixel Image::at(int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        return {};
    }
    return pixels_[y * width_ + x];
}

void Image::set(int x, int y, Pixel pixel) {
    if (x >= 0 && y >= 0 && x < width_ && y < height_) {
        pixels_[y * width_ + x] = pixel;
    }
}

double Image::luminance(int x, int y) const {
    const Pixel p = at(x, y);
    return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
}

std::vector<Place> shared_ink(const Image& a, const Image& b, int threshold) {
    std::vector<Place> shared;
    for (int y = 0; y < std::min(a.height(), b.height()); ++y) {
        for (int x = 0; x < std::min(a.width(), b.width()); ++x) {
            if (a.at(x, y).a >= threshold && b.at(x, y).a >= threshold) {
                shared.push_back({x, y});
            }
        }
    }
    return shared;
}

namespace {

// Any channel this far apart is a different pixel; antialiasing noise stays well below.
constexpr int kChannelTolerance = 48;

bool differ(const Pixel& a, const Pixel& b) {
    return std::abs(a.r - b.r) > kChannelTolerance || std::abs(a.g - b.g) > kChannelTolerance ||
           std::abs(a.b - b.b) > kChannelTolerance;
}

// A piece of text: the pixels of one connected patch of the text zone.
struct Patch {
    std::vector<Place> places;
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};

std::vector<Patch> patches(const std::vector<bool>& zone, int width, int height) {
    std::vector<Patch> found;
    std::vector<bool> seen(zone.size(), false);
    for (int start = 0; start < width * height; ++start) {
        if (!zone[start] || seen[start]) {
            continue;
        }
        Patch patch;
        std::vector<int> stack{start};
        seen[start] = true;
        while (!stack.empty()) {
            const int at = stack.back();
            stack.pop_back();
            const int x = at % width, y = at / width;
            patch.places.push_back({x, y});
            patch.x0 = std::min(patch.x0, x);
            patch.y0 = std::min(patch.y0, y);
            patch.x1 = std::max(patch.x1, x);
            patch.y1 = std::max(patch.y1, y);
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height) {
                        continue;
                    }
                    const int next = ny * width + nx;
                    if (zone[next] && !seen[next]) {
                        seen[next] = true;
                        stack.push_back(next);
                    }
                }
            }
        }
        found.push_back(std::move(patch));
    }
    return found;
}

// A patch's text as contrast against what lies under it, on a grid one pixel wider on each side.
struct Contrast {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<double> values;

    double& at(int x, int y) { return values[(y - y0) * width + x - x0]; }
    double at(int x, int y) const {
        return x < x0 || y < y0 || x >= x0 + width || y >= y0 + height
                   ? 0.0
                   : values[(y - y0) * width + x - x0];
    }
    double mass() const {
        double sum = 0.0;
        for (const double value : values) {
            sum += value;
        }
        return sum;
    }
    // Where its ink is centred.
    std::pair<double, double> centre() const {
        double x = 0.0, y = 0.0;
        for (int row = 0; row < height; ++row) {
            for (int column = 0; column < width; ++column) {
                x += column * values[row * width + column];
                y += row * values[row * width + column];
            }
        }
        return {x / mass(), y / mass()};
    }
    // Blurred over 3x3 pixels (weights 1 2 1), so that a lighter or heavier stroke weighs less
    // than a stroke out of place.
    double blurred(int x, int y) const {
        double sum = 0.0;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                sum += at(x + dx, y + dy) * (dx == 0 ? 2 : 1) * (dy == 0 ? 2 : 1);
            }
        }
        return sum / 16;
    }
};

Contrast contrast(const Patch& patch, const Image& image, const Image& under) {
    Contrast result{
        patch.x0 - 1, patch.y0 - 1, patch.x1 - patch.x0 + 3, patch.y1 - patch.y0 + 3, {}};
    result.values.assign(static_cast<std::size_t>(result.width * result.height), 0.0);
    for (const auto& [x, y] : patch.places) {
        result.at(x, y) = std::abs(image.luminance(x, y) - under.luminance(x, y));
    }
    return result;
}

// How far a piece of text may stray from the golden's. Rasterisers differ in stroke weight;
// text is placed on whole pixels, so where glyphs sit does not differ. Measured between cairo
// 1.16 (Debian 12) and 1.18 (Debian 13): no difference at all. A glyph one pixel away moves
// the ink's centre by a pixel; another digit or letter changes the blurred ink by 52 or more.
constexpr double kInkRatioLow = 0.8, kInkRatioHigh = 1.25;
constexpr double kCentreShift = 0.5;     // pixels
constexpr double kShapeDifference = 40;  // of 255, blurred

std::string text_difference(const Patch& patch, const Image& golden, const Image& drawn,
                            const Image& under) {
    const auto expected = contrast(patch, golden, under);
    const auto got = contrast(patch, drawn, under);
    char text[160];
    const double ratio = expected.mass() > 0 ? got.mass() / expected.mass() : 0.0;
    if (expected.mass() <= 0 || ratio < kInkRatioLow || ratio > kInkRatioHigh) {
        std::snprintf(text, sizeof text, "%.2f times the golden's ink (%.2f to %.2f allowed)",
                      ratio, kInkRatioLow, kInkRatioHigh);
        return text;
    }
    const auto [ex, ey] = expected.centre();
    const auto [gx, gy] = got.centre();
    const double shift = std::hypot(gx - ex, gy - ey);
    if (shift > kCentreShift) {
        std::snprintf(text, sizeof text, "moved by %.2f pixels (%.1f allowed)", shift,
                      kCentreShift);
        return text;
    }
    double worst = 0.0;
    for (int y = expected.y0; y < expected.y0 + expected.height; ++y) {
        for (int x = expected.x0; x < expected.x0 + expected.width; ++x) {
            worst = std::max(worst, std::abs(expected.blurred(x, y) - got.blurred(x, y)));
        }
    }
    if (worst > kShapeDifference) {
        std::snprintf(text, sizeof text, "its shape differs by %.0f of 255 (%.0f allowed)", worst,
                      kShapeDifference);
        return text;
    }
    return "";
}

}  // namespace

GoldenCheck::GoldenCheck(const pictures::Drawing& picture)
    : text_ink_(Image::ink_of(picture, picture.text_layers())),
      under_(Image::of(picture, pictures::all_layers & ~picture.text_layers())) {}

std::string GoldenCheck::differences(const Image& golden, const Image& drawn) const {
    std::ostringstream problems;
    if (golden.width() != drawn.width() || golden.height() != drawn.height()) {
        problems << "size " << drawn.width() << "x" << drawn.height() << ", golden "
                 << golden.width() << "x" << golden.height() << "\n";
        return problems.str();
    }
    const Image& text_ink = text_ink_;
    const Image& under = under_;
    const int width = drawn.width(), height = drawn.height();
    // The text zone: the text's ink and a pixel around it.
    std::vector<bool> zone(static_cast<std::size_t>(width * height), false);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (text_ink.at(x, y).a == 0) {
                continue;
            }
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    if (x + dx >= 0 && y + dy >= 0 && x + dx < width && y + dy < height) {
                        zone[(y + dy) * width + x + dx] = true;
                    }
                }
            }
        }
    }
    int differing = 0;
    Place first;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!zone[y * width + x] && differ(golden.at(x, y), drawn.at(x, y))) {
                if (differing++ == 0) {
                    first = {x, y};
                }
            }
        }
    }
    if (differing > 0) {
        problems << differing << " pixels of lines and shapes differ, the first at (" << first.x
                 << "," << first.y << ")\n";
    }
    for (const auto& patch : patches(zone, width, height)) {
        const auto problem = text_difference(patch, golden, drawn, under);
        if (!problem.empty()) {
            problems << "text at (" << patch.x0 << "," << patch.y0 << ")-(" << patch.x1 << ","
                     << patch.y1 << "): " << problem << "\n";
        }
    }
    return problems.str();
}

}  // namespace vibscore::testing
