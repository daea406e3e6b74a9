// Smooth conductor: a perfect mirror weighted by the exact conductor Fresnel reflectance with a
// complex index η + iκ per wavelength (pbrt-v4 §9.3.6). Mitsuba 3 plugin "conductor":
//   material              named conductor ("Au", "Ag", ..., "none" = perfect mirror; default "none")
//   eta, k                η and κ spectra instead of `material` (Unbounded; both together)
//   specular_reflectance  scale factor (spectrum or texture, default 1)
//   ext_ior               outside medium (float or preset name, default 1; iris extension)
// RGB mode: η and κ spectra are evaluated at the channel wavelengths (spectral/spectrum.h).
#include "core/registry.h"
#include "spectral/conductor_presets.h"
#include "materials/fresnel.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class ConductorBSDF final : public BSDF {
public:
    ConductorBSDF(const SampledSpectrum& eta, const SampledSpectrum& k, const SampledSpectrum& scale, bool mirror)
        : eta_(eta), k_(k), scale_(scale), mirror_(mirror) {}

    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(scale_.size()); }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2&, TransportMode) const override {
        if (wo.z <= 0) return std::nullopt;
        BSDFSample s;
        s.wi = reflectLocal(wo);
        s.pdf = 1.0f;
        const SampledSpectrum F = mirror_ ? SampledSpectrum(scale_.size(), 1.0f) : fresnelConductor(wo.z, eta_, k_);
        s.f = F * scale_ / s.wi.z;  // delta lobe: coefficient / |cosθi|
        s.flags = kBSDFReflection | kBSDFSpecular;
        return s;
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFSpecular; }
    /// Mitsuba 3 conductor.cpp, polarized: the complex Fresnel reflection matrix (its "none", the
    /// perfect mirror, is the index 0 + 1i: |r_s| = |r_p| = 1 with a phase difference).
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        const int n = scale_.size();
        const SampledSpectrum eta = mirror_ ? SampledSpectrum(n) : eta_, k = mirror_ ? SampledSpectrum(n, 1.0f) : k_;
        return withMueller(s, fresnelReflectionMueller(vec3(0, 0, 1), s->wi, wo, eta, &k), scale_ / s->wi.z);
    }

private:
    SampledSpectrum eta_, k_, scale_;
    bool mirror_;
};

class ConductorMaterial final : public Material {
public:
    ConductorMaterial(ConductorIOR c, SpectrumTexturePtr scale) : c_(std::move(c)), scale_(std::move(scale)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        SampledSpectrum eta, k;
        c_.sample(wl, &eta, &k);
        return arena.make<ConductorBSDF>(eta, k, scale_->eval(sp.tex, wl), c_.mirror);
    }

private:
    ConductorIOR c_;
    SpectrumTexturePtr scale_;
};

std::shared_ptr<Material> createConductor(const Properties& p) {
    ConductorIOR c = readConductor(p);
    return std::make_shared<ConductorMaterial>(
        std::move(c), getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "conductor", createConductor);

}  // namespace iris
