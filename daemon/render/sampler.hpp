#pragma once

#include <cstdint>
#include <span>

#include "daemon/render/performance.hpp"

namespace vibscore::render {

// The first sample index k whose time k / rate is at or after t. A performance of duration d
// has sample_index_at(d, rate) samples.
std::uint64_t sample_index_at(double t, double rate);

// Fills out[i] with the performance's signal at t = (first + i) / rate: the same values as
// Performance::value_at, computed fast enough to stream in real time on a small CPU.
void render_signal(const Performance& performance, double rate, std::uint64_t first,
                   std::span<double> out);

// As render_signal, for Performance::envelope_at.
void render_envelope(const Performance& performance, double rate, std::uint64_t first,
                     std::span<double> out);

}  // namespace vibscore::render
