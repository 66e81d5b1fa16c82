#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "daemon/render/sampler.hpp"
#include "tests/support/support.hpp"

namespace vibscore::render {
namespace {

// A score with every kind of tone: steady and gliding sines, curve and line shapes with a
// cross-fade, crescendo, legato, rests, and clef changes with different tempos.
Performance mixed_performance() {
    const std::string curve =
        "<VibClef type=\"curve\"><Tempo>0.13</Tempo><Numbers><Number>0.5</Number><Number>1</Number>"
        "</Numbers><Strings>"
        "<String><Point time=\"0\" level=\"0\"/><Point time=\"0.3\" level=\"1\"/>"
        "<Point time=\"0.6\" level=\"0.2\"/><Point time=\"1\" level=\"0\"/></String>"
        "<String><Point time=\"0\" level=\"1\"/><Point time=\"0.5\" level=\"1\"/>"
        "<Point time=\"0.5\" level=\"0\"/><Point time=\"1\" level=\"0.5\"/></String>"
        "</Strings></VibClef>";
    const std::string score = R"(<VibScore>
  <Clef id="s" href="s.xml"/><Clef id="k" href="k.xml"/>
  <Bar clef="s">
    <Note length="8th" number="1" string="1" dynamics="crescendo"/>
    <Note length="8th_dot" number="2" string="2" legato="1"/>
    <Note length="16th" number="3" string="3" legato="1" portamento="2"/>
    <Note length="quarter" number="1" string="1" portamento="2"/>
    <Rest length="32th"/>
    <Note length="half" number="2" string="3" dynamics="decrescendo"/>
  </Bar>
  <Bar clef="k">
    <Note length="half" number="2" string="1" portamento="5"/>
    <Note length="quarter_dot" number="1" string="2" portamento="5"/>
    <Note length="whole" number="2" string="2"/>
  </Bar>
</VibScore>)";
    return Performance(testing::bundle_from(
        score,
        {{"s.xml", testing::sine_clef(0.31, {97, 173.5, 251}, {0.5, 1, 1.5})}, {"k.xml", curve}}));
}

TEST(Sampler, SignalMatchesValueAtEverySample) {
    const auto performance = mixed_performance();
    const double rate = 8000.0;
    std::vector<double> samples(static_cast<std::size_t>(performance.duration() * rate) + 50);
    render_signal(performance, rate, 0, samples);
    double worst = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        worst = std::max(worst, std::abs(samples[k] - performance.value_at(k / rate)));
    }
    EXPECT_LT(worst, 1e-11);
}

TEST(Sampler, EnvelopeMatchesEnvelopeAtEverySample) {
    const auto performance = mixed_performance();
    const double rate = 1000.0;
    std::vector<double> samples(static_cast<std::size_t>(performance.duration() * rate) + 50);
    render_envelope(performance, rate, 0, samples);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        ASSERT_NEAR(samples[k], performance.envelope_at(k / rate), 1e-12) << k;
    }
}

TEST(Sampler, ChunkedRenderingEqualsOneShotRendering) {
    const auto performance = mixed_performance();
    const double rate = 44100.0;
    const auto total = static_cast<std::size_t>(performance.duration() * rate);
    std::vector<double> whole(total);
    render_signal(performance, rate, 0, whole);
    std::vector<double> pieces(total);
    std::size_t done = 0;
    for (std::size_t size = 1; done < total; size = size * 3 + 7) {
        const std::size_t n = std::min(size, total - done);
        render_signal(performance, rate, done, std::span(pieces).subspan(done, n));
        done += n;
    }
    for (std::size_t k = 0; k < total; ++k) {
        ASSERT_NEAR(pieces[k], whole[k], 1e-12) << k;
    }
}

TEST(Sampler, IsSilentBeforeAndAfterThePerformance) {
    const auto performance = mixed_performance();
    std::vector<double> samples(100, 7.0);
    const auto after = static_cast<std::uint64_t>(performance.duration() * 1000) + 1;
    render_signal(performance, 1000.0, after, samples);
    for (const double y : samples) {
        EXPECT_EQ(y, 0.0);
    }
}

TEST(Sampler, ReachesPeakAmplitudeButNeverExceedsIt) {
    const auto performance = mixed_performance();
    std::vector<double> samples(static_cast<std::size_t>(performance.duration() * 8000));
    render_signal(performance, 8000.0, 0, samples);
    double peak = 0.0;
    for (const double y : samples) {
        peak = std::max(peak, std::abs(y));
    }
    EXPECT_LE(peak, performance.peak_amplitude() + 1e-12);
    EXPECT_GT(peak, 0.9 * performance.peak_amplitude());
}

}  // namespace
}  // namespace vibscore::render
