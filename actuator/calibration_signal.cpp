// The recording's time line and vibration, and the minimiser the fits share.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "actuator/calibration_fit.hpp"

namespace vibscore::actuator::calibration::fit {

double median_rate(const std::vector<double>& t_s) {
    if (t_s.size() < 2) {
        return 0.0;
    }
    // Over the whole recording, not one interval: jittered timestamps make single intervals
    // wander, and the median of the spans of many readings does not.
    std::vector<double> spans;
    const std::size_t stride = std::max<std::size_t>(1, std::min<std::size_t>(16, t_s.size() / 8));
    for (std::size_t i = 0; i + stride < t_s.size(); ++i) {
        spans.push_back((t_s[i + stride] - t_s[i]) / static_cast<double>(stride));
    }
    if (spans.empty()) {
        return 0.0;
    }
    std::nth_element(spans.begin(), spans.begin() + spans.size() / 2, spans.end());
    const double interval = spans[spans.size() / 2];
    return interval > 0.0 ? 1.0 / interval : 0.0;
}

std::vector<double> regular_times(const std::vector<double>& t_s) {
    const double n = static_cast<double>(t_s.size());
    if (t_s.size() < 2) {
        // Element by element: GCC 14 takes a copy of a one-element vector here for an
        // out-of-bounds memmove (-Warray-bounds, a false positive that -Werror makes fatal).
        std::vector<double> few(t_s.size());
        for (std::size_t i = 0; i < t_s.size(); ++i) {
            few[i] = t_s[i];
        }
        return few;
    }
    double mean_i = (n - 1.0) / 2.0, mean_t = 0.0;
    for (const double t : t_s) {
        mean_t += t;
    }
    mean_t /= n;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < t_s.size(); ++i) {
        const double di = static_cast<double>(i) - mean_i;
        sxy += di * (t_s[i] - mean_t);
        sxx += di * di;
    }
    const double slope = sxy / sxx;
    std::vector<double> out(t_s.size());
    for (std::size_t i = 0; i < t_s.size(); ++i) {
        out[i] = mean_t + slope * (static_cast<double>(i) - mean_i);
    }
    return out;
}

std::vector<double> box_smooth(const std::vector<double>& values, int half) {
    const long n = static_cast<long>(values.size());
    std::vector<double> prefix(values.size() + 1, 0.0);
    for (long i = 0; i < n; ++i) {
        prefix[i + 1] = prefix[i] + values[i];
    }
    std::vector<double> out(values.size());
    for (long i = 0; i < n; ++i) {
        const long lo = std::max(0L, i - half), hi = std::min(n - 1, i + half);
        out[i] = (prefix[hi + 1] - prefix[lo]) / static_cast<double>(hi - lo + 1);
    }
    return out;
}

std::vector<Vec3> high_pass(const std::vector<Sample>& samples, int half) {
    std::vector<Vec3> out(samples.size());
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> v(samples.size());
        for (std::size_t i = 0; i < samples.size(); ++i) {
            v[i] = axis == 0 ? samples[i].x : axis == 1 ? samples[i].y : samples[i].z;
        }
        // Twice a box: a triangle, whose side lobes (5 %) let little of the vibration into
        // what is taken away, where a single box's (22 %) would.
        const std::vector<double> slow = box_smooth(box_smooth(v, half), half);
        for (std::size_t i = 0; i < samples.size(); ++i) {
            out[i][axis] = v[i] - slow[i];
        }
    }
    return out;
}

Vec3 principal_axis(const std::vector<Vec3>& vibration) {
    double c[3][3]{};
    for (const Vec3& v : vibration) {
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                c[i][j] += v[i] * v[j];
            }
        }
    }
    int largest = 0;
    for (int i = 1; i < 3; ++i) {
        if (c[i][i] > c[largest][largest]) {
            largest = i;
        }
    }
    Vec3 axis{0.0, 0.0, 0.0};
    axis[largest] = 1.0;
    for (int iteration = 0; iteration < 200; ++iteration) {
        Vec3 next{0.0, 0.0, 0.0};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                next[i] += c[i][j] * axis[j];
            }
        }
        const double n = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
        if (!(n > 0.0)) {
            break;
        }
        for (int i = 0; i < 3; ++i) {
            axis[i] = next[i] / n;
        }
    }
    return axis;
}

Vec3 principal_spread(const std::vector<Vec3>& vibration) {
    double c[3][3]{};
    for (const Vec3& v : vibration) {
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                c[i][j] += v[i] * v[j];
            }
        }
    }
    // Jacobi rotations: a 3x3 symmetric matrix converges in a handful of sweeps.
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = c[0][1] * c[0][1] + c[0][2] * c[0][2] + c[1][2] * c[1][2];
        if (off <= 1e-30 * (c[0][0] * c[0][0] + c[1][1] * c[1][1] + c[2][2] * c[2][2]) ||
            off == 0.0) {
            break;
        }
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (c[p][q] == 0.0) {
                    continue;
                }
                const double theta = 0.5 * std::atan2(2.0 * c[p][q], c[q][q] - c[p][p]);
                const double cs = std::cos(theta), sn = std::sin(theta);
                for (int k = 0; k < 3; ++k) {  // columns
                    const double a = c[k][p], b = c[k][q];
                    c[k][p] = cs * a - sn * b;
                    c[k][q] = sn * a + cs * b;
                }
                for (int k = 0; k < 3; ++k) {  // rows
                    const double a = c[p][k], b = c[q][k];
                    c[p][k] = cs * a - sn * b;
                    c[q][k] = sn * a + cs * b;
                }
            }
        }
    }
    Vec3 out{c[0][0], c[1][1], c[2][2]};
    std::sort(out.begin(), out.end(), std::greater<>());
    return out;
}

std::vector<double> minimise(const std::function<double(const std::vector<double>&)>& f,
                             std::vector<double> start, const std::vector<double>& step,
                             int iterations) {
    const std::size_t n = start.size();
    std::vector<std::vector<double>> points(n + 1, start);
    std::vector<double> values(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
        points[i + 1][i] += step[i];
    }
    for (std::size_t i = 0; i <= n; ++i) {
        values[i] = f(points[i]);
    }
    std::vector<std::size_t> order(n + 1);
    for (int iteration = 0; iteration < iterations; ++iteration) {
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
        const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
        std::vector<double> centre(n, 0.0);
        for (std::size_t k = 0; k < n; ++k) {
            for (std::size_t i = 0; i < n; ++i) {
                centre[i] += points[order[k]][i] / static_cast<double>(n);
            }
        }
        const auto along = [&](double factor) {
            std::vector<double> p(n);
            for (std::size_t i = 0; i < n; ++i) {
                p[i] = centre[i] + factor * (points[worst][i] - centre[i]);
            }
            return p;
        };
        const std::vector<double> reflected = along(-1.0);
        const double fr = f(reflected);
        if (fr < values[best]) {
            const std::vector<double> expanded = along(-2.0);
            const double fe = f(expanded);
            if (fe < fr) {
                points[worst] = expanded;
                values[worst] = fe;
            } else {
                points[worst] = reflected;
                values[worst] = fr;
            }
        } else if (fr < values[second]) {
            points[worst] = reflected;
            values[worst] = fr;
        } else {
            const std::vector<double> contracted = along(0.5);
            const double fc = f(contracted);
            if (fc < values[worst]) {
                points[worst] = contracted;
                values[worst] = fc;
            } else {
                for (std::size_t k = 0; k <= n; ++k) {
                    if (k == best) {
                        continue;
                    }
                    for (std::size_t i = 0; i < n; ++i) {
                        points[k][i] = points[best][i] + 0.5 * (points[k][i] - points[best][i]);
                    }
                    values[k] = f(points[k]);
                }
            }
        }
    }
    const auto best = std::min_element(values.begin(), values.end()) - values.begin();
    return points[best];
}

}  // namespace vibscore::actuator::calibration::fit
