// Sampling shared by the cloth BSDFs (cloth, velvet): directions ∝ sqrt(cosθ) over the upper
// hemisphere (cloth_distributions.h), weighted by the BSDF's own eval. Cosine sampling would give
// the wrapped-diffuse term infinite variance; this density has no jump at the horizon.
#pragma once

#include "materials/bsdf.h"
#include "materials/cloth_distributions.h"

namespace iris::cloth {

class SqrtCosineSampledBSDF : public BSDF {
public:
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        BSDFSample s;
        s.wi = sampleSqrtCosineHemisphere(u);
        s.pdf = sqrtCosineHemispherePdf(s.wi.z);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        s.flags = kBSDFReflection | kBSDFGlossy;
        return s;
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z < kMinCosTheta) return 0.0f;
        return sqrtCosineHemispherePdf(wi.z);
    }

protected:
    ~SqrtCosineSampledBSDF() = default;
};

}  // namespace iris::cloth
