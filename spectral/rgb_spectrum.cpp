#include "spectral/rgb_spectrum.h"

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/cie_tables.h"
#include "spectral/color_space.h"
#include "spectral/lane_dispatch.h"

namespace iris {

RGBSpectrum::RGBSpectrum(const vec3& rgb, SpectrumKind kind) : Spectrum(kind), rgb_(rgb) {
    if (!isFinite(rgb)) fail("RGB spectrum: non-finite value (", rgb.x, ", ", rgb.y, ", ", rgb.z, ")");
    vec3 shape;
    if (kind == SpectrumKind::Reflectance) {
        shape = glm::clamp(rgb, 0.0f, 1.0f);
        scale_ = 1.0f;
        // Near-black colours: fit the same chromaticity at brightness kDarkLevel and scale down.
        // The projection is linear, so the RGB is still reproduced, and s stays in [0, 1]; a direct
        // fit of e.g. (1e-6, 0, 0) needs huge coefficients (slow, and a bright invisible lobe).
        const float m = std::max({shape.x, shape.y, shape.z});
        if (m > 0.0f && m < kDarkLevel && !(shape.x == shape.y && shape.y == shape.z)) {
            scale_ = m / kDarkLevel;
            shape *= kDarkLevel / m;
        }
    } else {
        if (rgb.x == rgb.y && rgb.y == rgb.z) {
            // Unbounded greys keep their sign (scale factors may be negative).
            shape = vec3(kind == SpectrumKind::Illuminant ? std::max(rgb.x, 0.0f) : rgb.x);
        } else {
            shape = glm::max(rgb, vec3(0.0f));
        }
        const float m = std::max({shape.x, shape.y, shape.z});
        scale_ = m > 0.0f ? m : 1.0f;
        if (m > 0.0f) shape /= m;
    }
    if (kind == SpectrumKind::Illuminant) d65Scale_ = float(d65YNormalisation());

    if (shape.x == shape.y && shape.y == shape.z) {
        grey_ = true;
        level_ = shape.x;
    } else {
        const SigmoidFit fit = fitSigmoidPolynomial(shape);
        poly_ = fit.poly;
        fitError_ = fit.error;
    }

    float shapeMax = grey_ ? level_ : poly_.maxValue();
    if (kind == SpectrumKind::Illuminant) {
        float d65Max = 0;
        for (int i = 0; i < cie::tables::kD65Count; ++i) d65Max = std::max(d65Max, cie::tables::kD65[i]);
        shapeMax *= d65Scale_ * d65Max;
    }
    max_ = scale_ * shapeMax;
}

float RGBSpectrum::eval(float lambda) const {
    float v = shapeValue(lambda);
    if (d65Scale_ != 0.0f) v *= d65Scale_ * cie::d65(lambda);
    return v;
}

namespace {
// v = scale · s(λ) [· (d65Scale · D65(λ)) when d65 is given], the operations of eval in its order,
// for `padded` lanes; baseline and AVX2 builds (spectral/lane_dispatch.h).
IRIS_LANES_INLINE void sigmoidLanesBody(const SigmoidPolynomial& p, float scale, float d65Scale, const float* lambda,
                                        const float* d65, int padded, float* v) {
    const SigmoidPolynomial q = p;
    for (int i = 0; i < padded; ++i) v[i] = scale * q(lambda[i]);
    if (d65)
        for (int i = 0; i < padded; ++i) v[i] *= d65Scale * d65[i];
}
IRIS_LANES_KERNEL(void, sigmoidLanes, sigmoidLanesBody,
                  (const SigmoidPolynomial& p, float scale, float d65Scale, const float* lambda, const float* d65,
                   int padded, float* v),
                  (p, scale, d65Scale, lambda, d65, padded, v))
}  // namespace

SampledSpectrum RGBSpectrum::sample(const SampledWavelengths& wl) const {
    SampledSpectrum s(wl.size());
    if (wl.isRGB()) {
        // Bit-exact RGB mode: the triple as given, for every kind.
        for (int i = 0; i < 3; ++i) s[i] = rgb_[i];
        return s;
    }
    // eval at every lane, in lane loops the compiler vectorises (SSE2: 4 wavelengths per
    // instruction, the sigmoid's sqrt and division included). The operations per lane are those
    // of eval, in the same order: the same values (tests/spectral/test_rgb_upsampling.cpp). The D65 factor
    // is read from the values cached when the wavelengths were sampled (= cie::d65(λ)).
    const int padded = SampledSpectrum::paddedSize(wl.size());
    const float d65Scale = d65Scale_;
    const float* d65 = d65Scale != 0.0f ? wl.d65Lanes() : nullptr;
    if (grey_) {
        float* v = s.lanes();
        const float c = scale_ * level_;
        for (int i = 0; i < padded; ++i) v[i] = c;
        if (d65)
            for (int i = 0; i < padded; ++i) v[i] *= d65Scale * d65[i];
    } else {
        sigmoidLanes(lanes::useAvx2For(padded), poly_, scale_, d65Scale, wl.lambdas(), d65, padded, s.lanes());
    }
    return s;
}

}  // namespace iris
