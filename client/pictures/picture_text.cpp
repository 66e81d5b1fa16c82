#include "client/pictures/picture_text.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace vibscore::pictures {

void select_font(cairo_t* cairo, double size, bool bold) {
    cairo_select_font_face(cairo, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cairo, size);
    // Stated, not left to the surface: a PNG written after an SVG in one run was otherwise
    // hinted differently from one written alone. These are the image surface's defaults.
    const std::unique_ptr<cairo_font_options_t, decltype(&cairo_font_options_destroy)> options(
        cairo_font_options_create(), &cairo_font_options_destroy);
    cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
    cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_SLIGHT);
    cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_ON);
    cairo_set_font_options(cairo, options.get());
}

double text_width(cairo_t* cairo, const std::string& text) {
    cairo_text_extents_t extents;
    cairo_text_extents(cairo, text.c_str(), &extents);
    return extents.x_advance;
}

void show_text_at(cairo_t* cairo, double x, double y, const std::string& text) {
    cairo_move_to(cairo, std::round(x), std::round(y));
    cairo_show_text(cairo, text.c_str());
}

void show_centred(cairo_t* cairo, double x, double y, const std::string& text) {
    cairo_text_extents_t extents;
    cairo_text_extents(cairo, text.c_str(), &extents);
    show_text_at(cairo, x - extents.width / 2 - extents.x_bearing,
                 y - extents.height / 2 - extents.y_bearing, text);
}

namespace {

// The length of the UTF-8 character starting at text[at].
std::size_t character_length(const std::string& text, std::size_t at) {
    const auto lead = static_cast<unsigned char>(text[at]);
    const std::size_t length = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
    return std::min(length, text.size() - at);
}

}  // namespace

std::string fitted_text(cairo_t* cairo, const std::vector<std::string>& choices, double room) {
    for (const auto& choice : choices) {
        if (text_width(cairo, choice) <= room) {
            return choice;
        }
    }
    return "";
}

std::string elided_text(cairo_t* cairo, const std::string& text, double room) {
    if (text_width(cairo, text) <= room) {
        return text;
    }
    const std::string ellipsis = "\u2026";
    std::string kept;
    for (std::size_t at = 0; at < text.size();) {
        const auto length = character_length(text, at);
        const std::string longer = kept + text.substr(at, length);
        if (text_width(cairo, longer + ellipsis) > room) {
            break;
        }
        kept = longer;
        at += length;
    }
    return text_width(cairo, kept + ellipsis) <= room ? kept + ellipsis : "";
}

}  // namespace vibscore::pictures
