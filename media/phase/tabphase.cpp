// Tabulated phase function (Mitsuba 3 `tabphase`, src/phase/tabphase.cpp): `values`, a string of
// comma- or space-separated values f_0 … f_{n−1} (n ≥ 2, finite, ≥ 0, not all 0) at the regularly
// spaced cosines μ_i = −1 + 2i/(n − 1) of the scattering angle (μ = 1 forward, μ = −wo·wi as
// phase_function.h), interpolated linearly between them and normalised as Mitsuba 3's
// ContinuousDistribution does:
//   p(μ) = f(μ) / (2π ∫₋₁¹ f(μ') dμ'),   ∫₋₁¹ f = Σ_i (f_i + f_{i+1}) / 2 · Δ,   Δ = 2/(n − 1).
// Sampled exactly: a segment with probability ∝ f_i + f_{i+1}, then the position in it by
// inverting the linear density's CDF, t = ξ(a + b) / (a + sqrt((1 − ξ)a² + ξb²)) for end values
// a, b (pbrt-v4's SampleLinear, util/sampling.h), and the azimuth uniformly.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/sampling.h"
#include "media/phase/phase_function.h"
#include "media/phase/phase_sampling.h"

namespace iris {
namespace {

class TabulatedPhase final : public PhaseFunction {
public:
    explicit TabulatedPhase(std::vector<float> f) : f_(std::move(f)), step_(2.0f / float(f_.size() - 1)) {
        std::vector<float> mass(f_.size() - 1);
        double integral = 0;
        for (size_t i = 0; i + 1 < f_.size(); ++i) {
            mass[i] = f_[i] + f_[i + 1];
            integral += 0.5 * (double(f_[i]) + double(f_[i + 1])) * step_;
        }
        segments_ = Distribution1D(mass);
        norm_ = float(1.0 / (2.0 * kPi * integral));
    }

    float eval(const vec3&, const vec3& wo, const vec3& wi) const override { return value(-glm::dot(wo, wi)); }
    float pdf(const vec3&, const vec3& wo, const vec3& wi) const override { return value(-glm::dot(wo, wi)); }
    std::optional<PhaseSample> sample(const vec3&, const vec3& wo, const vec2& u) const override {
        float ur = 0.0f;
        const int i = segments_.sampleDiscrete(u.x, nullptr, &ur);
        const float a = f_[size_t(i)], b = f_[size_t(i) + 1];
        const float den = a + std::sqrt((1.0f - ur) * a * a + ur * b * b);
        const float t = den > 0 ? std::min(ur * (a + b) / den, 1.0f) : 0.0f;
        const vec3 wi = directionWithScatteringCosine(wo, -1.0f + (float(i) + t) * step_, u.y);
        const float p = value(-glm::dot(wo, wi));
        if (!(p > 0)) return std::nullopt;
        return PhaseSample{wi, p, p};
    }

private:
    /// The normalised, linearly interpolated table at μ.
    float value(float mu) const {
        const float x = std::clamp((mu + 1.0f) / step_, 0.0f, float(f_.size() - 1));
        const size_t i = std::min(size_t(x), f_.size() - 2);
        const float t = x - float(i);
        return norm_ * ((1.0f - t) * f_[i] + t * f_[i + 1]);
    }

    std::vector<float> f_;
    float step_;
    float norm_ = 0.0f;
    Distribution1D segments_;
};

std::vector<float> parseValues(const Properties& p) {
    std::string text = p.getString("values");
    for (char& c : text)
        if (c == ',') c = ' ';
    std::istringstream in(text);
    std::vector<float> f;
    std::string token;
    while (in >> token) {
        size_t used = 0;
        float v = 0.0f;
        try {
            v = std::stof(token, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != token.size()) failAt(p.locationOf("values"), "tabphase: '", token, "' in values is not a number");
        if (!(std::isfinite(v) && v >= 0))
            failAt(p.locationOf("values"), "tabphase: value ", f.size(), " is ", token, " (values must be finite and >= 0)");
        f.push_back(v);
    }
    return f;
}

std::shared_ptr<PhaseFunction> createTabulated(const Properties& p) {
    std::vector<float> f = parseValues(p);
    if (f.size() < 2) failAt(p.locationOf("values"), "tabphase: values needs at least 2 entries, got ", f.size());
    double sum = 0;
    for (float v : f) sum += v;
    if (!(sum > 0)) failAt(p.locationOf("values"), "tabphase: the values are all 0");
    return std::make_shared<TabulatedPhase>(std::move(f));
}

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "tabphase", createTabulated);

}  // namespace iris
