#include "daemon/render/waveform.hpp"

#include <algorithm>
#include <stdexcept>

namespace vibscore::render {

namespace {

// Tangent at point i of the piece [begin, end) (indices into points), in level per unit tau.
double tangent(const std::vector<ClefPoint>& points, std::size_t i, std::size_t begin,
               std::size_t end) {
    const std::size_t before = i > begin ? i - 1 : i;
    const std::size_t after = i + 1 < end ? i + 1 : i;
    const double span = points[after].time - points[before].time;
    return span > 0.0 ? (points[after].level - points[before].level) / span : 0.0;
}

}  // namespace

Waveform::Waveform(ClefType type, const std::vector<ClefPoint>& points) {
    if (points.empty()) {
        throw std::invalid_argument("a waveform needs at least one point");
    }
    for (const auto& point : points) {
        if (point_times_.empty() || point_times_.back() != point.time) {
            point_times_.push_back(point.time);
        }
    }
    first_level_ = points.front().level;
    last_level_ = points.back().level;
    // Split at steps (equal times) into pieces of strictly increasing time.
    std::size_t begin = 0;
    while (begin < points.size()) {
        std::size_t end = begin + 1;
        while (end < points.size() && points[end].time > points[end - 1].time) {
            ++end;
        }
        for (std::size_t i = begin; i + 1 < end; ++i) {
            const auto& a = points[i];
            const auto& b = points[i + 1];
            Segment segment;
            segment.start = a.time;
            segment.width = b.time - a.time;
            segment.c0 = a.level;
            if (type == ClefType::curve) {
                const double m0 = tangent(points, i, begin, end) * segment.width;
                const double m1 = tangent(points, i + 1, begin, end) * segment.width;
                const double d = b.level - a.level;
                segment.c1 = m0;
                segment.c2 = 3.0 * d - 2.0 * m0 - m1;
                segment.c3 = -2.0 * d + m0 + m1;
            } else {
                segment.c1 = b.level - a.level;
            }
            segments_.push_back(segment);
        }
        begin = end;
    }
}

double Waveform::evaluate(const Segment& segment, double tau) const {
    const double s = (tau - segment.start) / segment.width;
    return segment.c0 + s * (segment.c1 + s * (segment.c2 + s * segment.c3));
}

double Waveform::level(double tau) const {
    std::size_t hint = 0;
    return level(tau, hint);
}

double Waveform::level(double tau, std::size_t& hint) const {
    if (segments_.empty() || tau < segments_.front().start) {
        return segments_.empty() ? last_level_ : first_level_;
    }
    const auto& last = segments_.back();
    if (tau >= last.start + last.width) {
        return last_level_;
    }
    if (hint >= segments_.size() || segments_[hint].start > tau) {
        hint = 0;
    }
    // Segments tile [first, last) without holes; at a step the later segment wins.
    while (hint + 1 < segments_.size() && segments_[hint + 1].start <= tau) {
        ++hint;
    }
    return evaluate(segments_[hint], tau);
}

}  // namespace vibscore::render
