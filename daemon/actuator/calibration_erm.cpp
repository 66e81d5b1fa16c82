// An ERM's spin-up and spin-down from a recording of its probe.
//
// The eccentric mass shakes the phone with a force that goes with the square of its speed, at a
// frequency that is its speed (fast, and aliased at the slower rates): its phase says nothing
// usable, its energy does. |vibration|^2 smoothed over a few milliseconds goes with speed^4;
// the model is the first-order speed under the plan (spin-up while driven, spin-down while
// coasting, a small delay), raised to the 4th power and smoothed by the very same moving
// average, so the smoothing shifts and rounds both alike and does not bias the time constants.
// The scale and the noise floor are linear least squares; the constants and delay are searched.
#include <algorithm>
#include <cmath>

#include "daemon/actuator/calibration_fit.hpp"

namespace vibscore::actuator::calibration::fit {

double erm_speed(const Plan& plan, double spin_up_s, double spin_down_s, double delay_s,
                 double t_s) {
    double speed = 0.0;
    for (std::size_t i = 0; i < plan.rows.size(); ++i) {
        const double start = plan.rows[i].t_s + delay_s;
        if (t_s <= start) {
            break;
        }
        const double end = i + 1 < plan.rows.size() ? plan.rows[i + 1].t_s + delay_s : INFINITY;
        const double dt = std::min(t_s, end) - start;
        const double u = plan.rows[i].amplitude;
        const double tau = u != 0.0 ? spin_up_s : spin_down_s;
        speed = u + (speed - u) * std::exp(-dt / tau);
    }
    return speed;
}

namespace {

struct Energy {
    const Plan& plan;
    const std::vector<double>& t;
    const std::vector<double>& energy;
    int half;

    // The residual, and the scale and floor that give it.
    double rss(double up, double down, double delay, double* scale = nullptr,
               double* floor = nullptr) const {
        std::vector<double> model(t.size());
        for (std::size_t k = 0; k < t.size(); ++k) {
            const double s = erm_speed(plan, up, down, delay, t[k]);
            model[k] = s * s * s * s;
        }
        model = box_smooth(model, half);
        double sm = 0.0, sy = 0.0, smm = 0.0, smy = 0.0, syy = 0.0;
        const double n = static_cast<double>(t.size());
        for (std::size_t k = 0; k < t.size(); ++k) {
            sm += model[k];
            sy += energy[k];
            smm += model[k] * model[k];
            smy += model[k] * energy[k];
            syy += energy[k] * energy[k];
        }
        const double var_m = smm - sm * sm / n;
        const double cov = smy - sm * sy / n;
        const double a = var_m > 0.0 ? cov / var_m : 0.0;
        const double c = (sy - a * sm) / n;
        if (scale) {
            *scale = a;
        }
        if (floor) {
            *floor = c;
        }
        return std::max(0.0, syy - sy * sy / n - a * cov);
    }
};

}  // namespace

ErmFit fit_erm(const Plan& plan, const std::vector<double>& t_s, const std::vector<double>& energy,
               int half) {
    const Energy model{plan, t_s, energy, half};
    // Coarse: both time constants on a log grid (5 ms .. 1.3 s), no delay.
    double best_up = 0.04, best_down = 0.08, best_delay = 0.0, best = 1e300;
    for (double up = 0.005; up < 0.6; up *= 1.15) {
        for (double down = 0.01; down < 1.3; down *= 1.15) {
            const double r = model.rss(up, down, 0.0);
            if (r < best) {
                best = r;
                best_up = up;
                best_down = down;
            }
        }
    }
    for (double delay = -0.05; delay <= 0.0501; delay += 0.002) {
        const double r = model.rss(best_up, best_down, delay);
        if (r < best) {
            best = r;
            best_delay = delay;
        }
    }
    const auto cost = [&](const std::vector<double>& p) {
        if (std::abs(p[2]) > 0.08) {
            return 1e300;
        }
        return model.rss(std::exp(p[0]), std::exp(p[1]), p[2]);
    };
    const std::vector<double> found = minimise(
        cost, {std::log(best_up), std::log(best_down), best_delay}, {0.1, 0.1, 0.003}, 150);
    ErmFit out;
    out.spin_up_s = std::exp(found[0]);
    out.spin_down_s = std::exp(found[1]);
    out.delay_s = found[2];
    out.rss = model.rss(out.spin_up_s, out.spin_down_s, out.delay_s, &out.scale, &out.floor);
    for (const double e : energy) {
        out.energy_ss += (e - out.floor) * (e - out.floor);
    }
    return out;
}

}  // namespace vibscore::actuator::calibration::fit
