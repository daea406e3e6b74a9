// Thin dielectric sheet (Mitsuba 3 plugin "thindielectric"): a slab whose two interfaces are
// parallel and close together, so light either reflects or passes straight through (no
// refraction offset). Summing the internal bounces (geometric series) gives
//   R' = R + T² R / (1 − R²),  T' = 1 − R'   (R = single-interface Fresnel, T = 1 − R).
// Parameters: int_ior ("bk7"), ext_ior ("air") (any form of spectral/ior_params.h),
// specular_reflectance, specular_transmittance (1).
// The lobe is chosen with the mean of R' over the wavelengths; no wavelength termination is
// needed since directions do not depend on η.
// The transmission is a pass-through lobe (kBSDFNull), as in Mitsuba 3 (thindielectric.cpp: its
// second component is BSDFFlags::Null, sampled_type Null, eval_null_transmission = 1 − R') and
// Mitsuba 0.6 (ENull): the volumetric integrators do not count it as a bounce and their shadow rays
// cross it with weight (1 − R')·specular_transmittance (nullTransmission). The `path` integrator
// treats it like any delta lobe (Mitsuba 3 path.cpp: every intersection is a bounce, and shadow rays
// are plain occlusion tests).
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/fresnel_polarized.h"
#include "materials/mueller_frames.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

class ThinDielectricBSDF final : public BSDF {
public:
    ThinDielectricBSDF(const SampledSpectrum& eta, const SampledSpectrum& r, const SampledSpectrum& t)
        : eta_(eta), r_(r), t_(t) {}

    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(r_.size()); }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2&, TransportMode) const override {
        if (wo.z == 0) return std::nullopt;
        const SampledSpectrum R = slabReflectance(wo);
        const float pR = std::clamp(R.average(), 0.0f, 1.0f);
        BSDFSample s;
        if (uc < pR) {
            s.wi = reflectLocal(wo);
            s.pdf = pR;
            s.f = R * r_ / std::abs(wo.z);
            s.flags = kBSDFReflection | kBSDFSpecular;
        } else {
            s.wi = -wo;
            s.pdf = 1.0f - pR;
            s.f = (1.0f - R) * t_ / std::abs(wo.z);
            s.flags = kBSDFNull | kBSDFTransmission | kBSDFSpecular;
        }
        return s;
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFNull | kBSDFTransmission | kBSDFSpecular; }
    std::optional<SampledSpectrum> nullTransmission(const vec3& wo) const override {
        return (1.0f - slabReflectance(wo)) * t_;  // Mitsuba 3 eval_null_transmission: 1 − R'
    }

    /// Polarized: the slab's matrices per polarization (materials/fresnel_polarized.h slabTerms),
    /// for the lobe sample() chose with the unpolarized R'. Their response to unpolarized light,
    /// (R'_s + R'_p)/2, is not the unpolarized model's R' of the mean R: the slab sums s and p
    /// separately (docs/polarization.md).
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        const bool reflected = !s->isNull();
        MuellerSpectrum M = slabMueller(wo, s->wi, reflected) * ((reflected ? r_ : t_) / std::abs(wo.z));
        return PolarizedBSDFSample{*s, M};
    }
    std::optional<MuellerSpectrum> nullTransmissionMueller(const vec3& wo) const override {
        return slabMueller(wo, -wo, false) * t_;
    }

private:
    MuellerSpectrum slabMueller(const vec3& wo, const vec3& wi, bool reflected) const {
        const MuellerSpectrum M = interfaceMuellerPerLane(eta_.size(), [&](int i) {
            const SlabMuellerTerms t = slabTerms(wo.z, eta_[i]);
            return reflected ? t.reflection : t.transmission;
        });
        return fromSAxisBases(M, vec3(0, 0, 1), wi, wo);
    }
    /// R' = R + T²R/(1 − R²), the slab's reflectance with every internal bounce (R at |cos θo|).
    SampledSpectrum slabReflectance(const vec3& wo) const {
        SampledSpectrum R = fresnelDielectric(std::abs(wo.z), eta_);
        for (int i = 0; i < R.size(); ++i) {
            const float r = R[i], t = 1.0f - r;
            R[i] = r < 1.0f ? r + t * t * r / (1.0f - r * r) : 1.0f;
        }
        return R;
    }

    SampledSpectrum eta_, r_, t_;
};

class ThinDielectricMaterial final : public Material {
public:
    ThinDielectricMaterial(IOR in, IOR ext, SpectrumTexturePtr r, SpectrumTexturePtr t)
        : in_(std::move(in)), ext_(std::move(ext)), r_(std::move(r)), t_(std::move(t)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const SampledSpectrum eta = in_.sample(wl) / ext_.sample(wl);
        return arena.make<ThinDielectricBSDF>(eta, r_->eval(sp.tex, wl), t_->eval(sp.tex, wl));
    }
    bool transmitsShadowRays() const override { return true; }

private:
    IOR in_, ext_;
    SpectrumTexturePtr r_, t_;
};

std::shared_ptr<Material> createThinDielectric(const Properties& p) {
    auto [in, ext] = readInterfaceIOR(p);
    return std::make_shared<ThinDielectricMaterial>(
        std::move(in), std::move(ext), getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f),
        getSpectrumTexture(p, "specular_transmittance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "thindielectric", createThinDielectric);

}  // namespace iris
