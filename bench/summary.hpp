#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace vibscore::bench {

// What the benchmarks report of a set of samples, in the samples' unit. Percentiles are by
// nearest rank, so each is a value that was actually measured.
struct Summary {
    std::size_t n = 0;
    double mean = 0, p50 = 0, p99 = 0, max = 0;
};

inline Summary summarize(std::vector<double> samples) {
    Summary summary;
    summary.n = samples.size();
    if (samples.empty()) {
        return summary;
    }
    std::sort(samples.begin(), samples.end());
    const auto rank = [&](double p) {
        const auto index = static_cast<std::size_t>(std::ceil(p * static_cast<double>(summary.n)));
        return samples[std::clamp<std::size_t>(index, 1, summary.n) - 1];
    };
    summary.mean =
        std::accumulate(samples.begin(), samples.end(), 0.0) / static_cast<double>(summary.n);
    summary.p50 = rank(0.50);
    summary.p99 = rank(0.99);
    summary.max = samples.back();
    return summary;
}

// A summary of milliseconds as JSON members named `prefix`_n, _p50_ms, _p99_ms and _max_ms.
inline std::string json_summary(const char* prefix, const Summary& s) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "\"%s_n\":%zu,\"%s_p50_ms\":%.4f,\"%s_p99_ms\":%.4f,\"%s_max_ms\":%.4f", prefix,
                  s.n, prefix, s.p50, prefix, s.p99, prefix, s.max);
    return text;
}

}  // namespace vibscore::bench
