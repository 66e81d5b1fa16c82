// The staff and signal pictures: SVG that parses with one note head per note, PNG of the
// expected size with ink where the notes are, and thesis Fig. 2.3a's first measure against a
// committed golden image.
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <cmath>
#include <cstdio>

#include "client/pictures/signal_picture.hpp"
#include "client/pictures/staff_picture.hpp"
#include "score/bundle.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using pictures::SignalPicture;
using pictures::StaffPicture;
using testing::TempDir;

std::filesystem::path shipped(const std::string& name) {
    return std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / name;
}

std::filesystem::path golden(const std::string& name) {
    return std::filesystem::path(testing::required_env("VIBSCORE_GOLDEN")) / name;
}

std::size_t count_notes(const Score& score) {
    return testing::notes_in(score).size();
}

// cairo writes colours as percentages: rgb(8%,8%,25%).
std::string head_stroke() {
    char text[64];
    std::snprintf(text, sizeof text, "stroke:rgb(%g%%,%g%%,%g%%)", StaffPicture::head_ink[0] * 100,
                  StaffPicture::head_ink[1] * 100, StaffPicture::head_ink[2] * 100);
    return text;
}

struct Pixel {
    int r, g, b;
    bool white() const { return r > 245 && g > 245 && b > 245; }
};

Pixel pixel_at(cairo_surface_t* image, double x, double y) {
    const int stride = cairo_image_surface_get_stride(image);
    const unsigned char* data = cairo_image_surface_get_data(image);
    const auto* at = reinterpret_cast<const std::uint32_t*>(data + static_cast<int>(y) * stride) +
                     static_cast<int>(x);
    return {static_cast<int>(*at >> 16 & 0xFF), static_cast<int>(*at >> 8 & 0xFF),
            static_cast<int>(*at & 0xFF)};
}

pictures::SurfacePtr read_png(const std::filesystem::path& path) {
    pictures::SurfacePtr image(cairo_image_surface_create_from_png(path.c_str()),
                               &cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS) << path;
    return image;
}

TEST(StaffPicture, TheSvgParsesAndHoldsOneNoteHeadPerNote) {
    TempDir dir;
    for (const char* name :
         {"ode-to-joy.score.xml", "ringtone.score.xml", "delete-file.score.xml"}) {
        SCOPED_TRACE(name);
        const auto score = read_score(read_document_file(shipped(name)), name).score;
        const StaffPicture picture(score);
        const auto svg = dir.path() / "staff.svg";
        pictures::write_picture(picture, svg);
        pugi::xml_document document;
        ASSERT_TRUE(document.load_file(svg.c_str())) << testing::read_file(svg);
        ASSERT_STREQ(document.document_element().name(), "svg");
        std::size_t heads = 0;
        for (const auto& path : document.select_nodes("//path")) {
            heads += std::string(path.node().attribute("style").value()).find(head_stroke()) !=
                             std::string::npos
                         ? 1
                         : 0;
        }
        EXPECT_EQ(heads, count_notes(score));
        EXPECT_EQ(picture.head_centres().size(), count_notes(score));
    }
}

// Ode to Joy's staff, and the PNG it makes.
struct OdeToJoyPng {
    TempDir dir;
    Score score = read_score(read_document_file(shipped("ode-to-joy.score.xml")), "ode").score;
    StaffPicture picture{score};
    pictures::SurfacePtr image{nullptr, &cairo_surface_destroy};

    OdeToJoyPng() {
        const auto png = dir.path() / "staff.png";
        pictures::write_picture(picture, png);
        image = read_png(png);
    }
};

TEST(StaffPicture, ThePngHasItsSizeAndInkAtEveryNoteHead) {
    const OdeToJoyPng drawn;
    const auto& picture = drawn.picture;
    const auto& image = drawn.image;
    EXPECT_EQ(cairo_image_surface_get_width(image.get()), static_cast<int>(picture.width()));
    EXPECT_EQ(cairo_image_surface_get_height(image.get()), static_cast<int>(picture.height()));
    // A long score breaks into systems, so the picture is taller than one staff.
    EXPECT_GT(picture.height(), 2 * 120.0);
    for (const auto& head : picture.head_centres()) {
        // The head's outline, just inside its left edge, is ink whatever the head's fill.
        EXPECT_FALSE(pixel_at(image.get(), head.x - 6, head.y).white()) << head.x << "," << head.y;
    }
    EXPECT_TRUE(pixel_at(image.get(), 2, picture.height() - 2).white());
}

// Compares a drawn PNG with a committed one: the same size, and all but a few pixels alike.
void expect_like(const std::filesystem::path& committed, const std::filesystem::path& drawn) {
    const auto expected = read_png(committed);
    const auto got = read_png(drawn);
    const int width = cairo_image_surface_get_width(expected.get());
    const int height = cairo_image_surface_get_height(expected.get());
    ASSERT_EQ(cairo_image_surface_get_width(got.get()), width);
    ASSERT_EQ(cairo_image_surface_get_height(got.get()), height);
    // Font rasterising may shift a few antialiased pixels; the drawing itself may not move.
    int differing = 0, inked = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const auto a = pixel_at(expected.get(), x, y);
            const auto b = pixel_at(got.get(), x, y);
            inked += a.white() ? 0 : 1;
            if (std::abs(a.r - b.r) > 48 || std::abs(a.g - b.g) > 48 || std::abs(a.b - b.b) > 48) {
                ++differing;
            }
        }
    }
    EXPECT_GT(inked, width * height / 20);  // the committed image is a drawing, not a blank
    EXPECT_LE(differing, width * height / 200) << "of " << width * height << " pixels";
}

TEST(StaffPicture, Figure23aFirstMeasureMatchesTheGoldenImage) {
    TempDir dir;
    const auto drawn = dir.path() / "figure.png";
    const auto result =
        testing::run_command({testing::required_env("VIBSCORE"), "show",
                              golden("figure-2-3a.score.xml").string(), "--png", drawn.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    expect_like(golden("figure-2-3a-staff.png"), drawn);
}

// The README shows these two; the commands beside them must still draw them.
TEST(Pictures, TheReadmePicturesAreWhatTheirCommandsDraw) {
    TempDir dir;
    const auto pictures = shipped("..") / "docs" / "pictures";
    for (const char* verb : {"show", "render"}) {
        SCOPED_TRACE(verb);
        const auto name = std::string("ode-to-joy-") +
                          (verb == std::string("show") ? "staff" : "signal") + ".png";
        const auto drawn = dir.path() / name;
        const auto result = testing::run_command({testing::required_env("VIBSCORE"), verb,
                                                  shipped("ode-to-joy.score.xml").string(), "--png",
                                                  drawn.string()});
        ASSERT_EQ(result.exit_code, 0) << result.err;
        expect_like(pictures / name, drawn);
    }
}

TEST(StaffPicture, TheClefBoxOfABarStartingTheNextSystemIsDrawnThereOnly) {
    const OdeToJoyPng drawn;
    const auto& image = drawn.image;
    // Every system ends at its closing bar line, inside the right margin: the margin's last
    // columns hold no ink, not the start of a box for the bar that opens the next system.
    const int width = cairo_image_surface_get_width(image.get());
    for (int y = 0; y < cairo_image_surface_get_height(image.get()); ++y) {
        for (int x = width - 6; x < width; ++x) {
            ASSERT_TRUE(pixel_at(image.get(), x, y).white()) << x << "," << y;
        }
    }
}

TEST(SignalPicture, DrawsTheSignalWhereNotesSoundAndNothingInRests) {
    const auto bundle = load_score_file(golden("figure-2-3a.score.xml"));
    const render::Performance performance(bundle);
    const SignalPicture picture(performance, "Fig. 2.3c");
    const auto image = pictures::render_image(picture);
    EXPECT_EQ(cairo_image_surface_get_width(image.get()), 960);
    EXPECT_EQ(cairo_image_surface_get_height(image.get()), 320);
    // Fig. 2.3c: an 8th at amplitude 1, a quarter at 2, an 8th rest, a half at 2 (tempo 1 s).
    const auto inked_column = [&](double t, double level) {
        int inked = 0;
        for (int dx = -3; dx <= 3; ++dx) {
            inked +=
                pixel_at(image.get(), picture.x_of(t) + dx, picture.y_of(level)).white() ? 0 : 1;
        }
        return inked;
    };
    EXPECT_GT(inked_column(1.0, 1.0), 0);   // inside the quarter at amplitude 2
    EXPECT_GT(inked_column(3.0, -1.5), 0);  // inside the half note
    EXPECT_EQ(inked_column(1.75, 1.0), 0);  // the 8th rest is silence
    EXPECT_EQ(inked_column(0.25, 1.5), 0);  // the first 8th never reaches 1.5
}

TEST(Pictures, TheFileFormatComesFromTheExtension) {
    EXPECT_EQ(pictures::picture_format_for("a.svg"), pictures::PictureFormat::svg);
    EXPECT_EQ(pictures::picture_format_for("dir/a.png"), pictures::PictureFormat::png);
    EXPECT_THROW(pictures::picture_format_for("a.jpg"), std::invalid_argument);
}

}  // namespace
}  // namespace vibscore
