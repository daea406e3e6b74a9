// Smooth dielectric interface: Fresnel-weighted choice between mirror reflection and refraction
// (pbrt-v4 §9.5; Mitsuba 3 plugin "dielectric"). Works from both sides (wo.z < 0 = inside).
//   int_ior  (default "bk7"), ext_ior (default "air"): any form of spectral/ior_params.h (float,
//            preset name, rgb per channel, spectrum, int_cauchy_*/int_sellmeier_*, ...)
//   specular_reflectance, specular_transmittance  scale factors (default 1)
// Transmission in Radiance mode is scaled by (η_i/η_t)² (non-symmetric BTDF, Veach 1997 §5.2).
// Directions use one η: the hero wavelength's in spectral mode (secondaries are terminated when η
// varies with λ), the green channel's in RGB mode; Fresnel factors use each channel's own η.
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

class DielectricBSDF final : public BSDF {
public:
    DielectricBSDF(const SampledSpectrum& eta, float etaDir, const SampledSpectrum& r, const SampledSpectrum& t)
        : eta_(eta), etaDir_(etaDir), r_(r), t_(t) {}

    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(r_.size()); }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2&, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const FresnelDielectricResult fr = fresnelDielectricFull(wo.z, etaDir_);
        const SampledSpectrum R = fresnelDielectric(wo.z, eta_);
        BSDFSample s;
        if (uc < fr.R) {
            s.wi = reflectLocal(wo);
            s.pdf = fr.R;
            s.f = R * r_ / std::abs(s.wi.z);
            s.flags = kBSDFReflection | kBSDFSpecular;
        } else {
            s.wi = refractLocal(wo, fr.cosThetaT, fr.etaTI);
            if (s.wi.z == 0) return std::nullopt;
            s.pdf = 1.0f - fr.R;
            // Importance mode is the adjoint: the reverse radiance sample's coefficient over η²
            // (Veach 1997 eq. 5.14), so no 1/η² and each channel's Fresnel factor seen from wi
            // (equal to wo's where a channel's η is the one that bent the ray).
            const SampledSpectrum T =
                1.0f - (mode == TransportMode::Radiance ? R : fresnelDielectricAdjoint(wo.z, s.wi.z, eta_, etaDir_));
            s.f = T * t_ / std::abs(s.wi.z);
            if (mode == TransportMode::Radiance) s.f *= sqr(fr.etaTI);  // radiance compression 1/η²
            s.flags = kBSDFTransmission | kBSDFSpecular;
            s.eta = fr.etaIT;
        }
        return s;
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFTransmission | kBSDFSpecular; }
    /// Mitsuba 3 dielectric.cpp, polarized: the Fresnel reflection or refraction matrix of the
    /// sampled lobe, at the cosine of the light's side; f's other factors unchanged.
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        const vec3 n(0, 0, 1);
        if (!s->isTransmission()) return withMueller(s, fresnelReflectionMueller(n, s->wi, wo, eta_), r_ / std::abs(s->wi.z));
        const float etaTI = wo.z > 0 ? 1.0f / etaDir_ : etaDir_;
        const float radiance = mode == TransportMode::Radiance ? sqr(etaTI) : 1.0f;
        return withMueller(s, fresnelTransmissionMueller(n, s->wi, wo, eta_), t_ * (radiance / std::abs(s->wi.z)));
    }

private:
    SampledSpectrum eta_;
    float etaDir_;
    SampledSpectrum r_, t_;
};

class DielectricMaterial final : public Material {
public:
    DielectricMaterial(IOR in, IOR ext, SpectrumTexturePtr r, SpectrumTexturePtr t)
        : in_(std::move(in)), ext_(std::move(ext)), r_(std::move(r)), t_(std::move(t)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        SampledSpectrum eta;
        const float etaDir = relativeIOR(in_, ext_, wl, &eta);
        return arena.make<DielectricBSDF>(eta, etaDir, r_->eval(sp.tex, wl), t_->eval(sp.tex, wl));
    }

private:
    IOR in_, ext_;
    SpectrumTexturePtr r_, t_;
};

std::shared_ptr<Material> createDielectric(const Properties& p) {
    auto [in, ext] = readInterfaceIOR(p);
    return std::make_shared<DielectricMaterial>(
        std::move(in), std::move(ext), getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f),
        getSpectrumTexture(p, "specular_transmittance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "dielectric", createDielectric);

}  // namespace iris
