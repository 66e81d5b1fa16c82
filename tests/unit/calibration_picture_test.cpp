// The picture `vibscore calibrate --png/--svg` draws (client/pictures/calibration_picture.*): the
// recording, and the model with the measured numbers (solid) and the declared ones (dashed), each
// where its values put it, with a legend; and the picture a recording of a wrong declaration
// makes, through the client's offline path.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "actuator/vibration_sensor.hpp"
#include "client/calibrate_verb.hpp"
#include "client/pictures/calibration_picture.hpp"
#include "tests/support/support.hpp"
#include "tests/unit/picture_ink.hpp"

namespace vibscore {
namespace {

using pictures::CalibrationPicture;
using testing::Image;

// A flat trace at `level` over 0..1 s.
actuator::calibration::Trace flat(double level) {
    actuator::calibration::Trace trace;
    for (int k = 0; k <= 100; ++k) {
        trace.t_s.push_back(k / 100.0);
        trace.magnitude.push_back(level);
    }
    return trace;
}

int inked_rows_at(const Image& ink, int x) {
    int rows = 0;
    for (int y = 0; y < ink.height(); ++y) {
        rows += ink.at(x, y).a > 64 ? 1 : 0;
    }
    return rows;
}

TEST(CalibrationPicture, EachTraceIsDrawnAtItsLevelInItsOwnLayer) {
    const CalibrationPicture picture({flat(4.0), flat(2.0), flat(1.0)}, "calibration", "caption");
    const int x = static_cast<int>(picture.x_of(0.5));
    for (const auto& [layer, level] : std::vector<std::pair<CalibrationPicture::Layer, double>>{
             {CalibrationPicture::recorded, 4.0},
             {CalibrationPicture::fitted, 2.0},
             {CalibrationPicture::declared, 1.0}}) {
        const auto ink = Image::ink_of(picture, layer);
        const int y = static_cast<int>(std::lround(picture.y_of(level)));
        EXPECT_GT(ink.at(x, y).a + ink.at(x, y - 1).a + ink.at(x, y + 1).a, 64)
            << "layer " << layer << " at " << level;
        EXPECT_LE(inked_rows_at(ink, x), 4) << "one line, layer " << layer;
    }
}

TEST(CalibrationPicture, TheDeclaredModelIsDashedAndTheFittedOneSolid) {
    const CalibrationPicture picture({flat(4.0), flat(2.0), flat(1.0)}, "calibration", "caption");
    const auto gaps = [&](CalibrationPicture::Layer layer, double level) {
        const auto ink = Image::ink_of(picture, layer);
        const int y = static_cast<int>(std::lround(picture.y_of(level)));
        int empty = 0;
        for (int x = static_cast<int>(picture.x_of(0.1)); x < picture.x_of(0.9); ++x) {
            const int a = ink.at(x, y).a + ink.at(x, y - 1).a + ink.at(x, y + 1).a;
            empty += a < 16 ? 1 : 0;
        }
        return empty;
    };
    EXPECT_EQ(gaps(CalibrationPicture::fitted, 2.0), 0);
    EXPECT_GT(gaps(CalibrationPicture::declared, 1.0), 20);
}

TEST(CalibrationPicture, WithNothingDeclaredTheDeclaredLayerIsEmpty) {
    const CalibrationPicture picture({flat(4.0), flat(2.0), {}}, "calibration", "caption");
    const auto ink = Image::ink_of(picture, CalibrationPicture::declared);
    int inked = 0;
    for (int y = 0; y < ink.height(); ++y) {
        for (int x = 0; x < ink.width(); ++x) {
            inked += ink.at(x, y).a > 0 ? 1 : 0;
        }
    }
    EXPECT_EQ(inked, 0);
}

TEST(CalibrationPicture, TheClientWritesOneForARecordingOfAWrongDeclaration) {
    actuator::Declaration declared;
    declared.kind = actuator::Kind::lra;
    declared.resonance_hz = 175.0;
    declared.q = 15.0;
    auto truth = declared;
    truth.resonance_hz = 168.0;
    truth.q = 10.0;
    const auto plan = actuator::calibration::make_plan(actuator::Kind::lra, declared);
    const auto samples = actuator::record(plan, truth, actuator::SensorOptions{}, 0.0, 0.2);
    const auto estimate = actuator::calibration::estimate(plan, samples, declared);
    ASSERT_TRUE(estimate.trusted);
    testing::TempDir dir;
    const auto png = dir.path() / "fit.png";
    client::write_calibration_picture(png.string(), plan, samples, estimate, declared);
    const auto image = Image::read_png(png);
    EXPECT_EQ(image.width(), 960);
    EXPECT_EQ(image.height(), 340);
    EXPECT_THROW(client::write_calibration_picture((dir.path() / "fit.bmp").string(), plan, samples,
                                                   estimate, declared),
                 std::invalid_argument);
}

}  // namespace
}  // namespace vibscore
