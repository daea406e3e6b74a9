// The BSDF interface every material implements. All directions are unit vectors in the local
// shading frame (normal = +z) and point away from the surface: wo towards the viewer (or the
// previous path vertex), wi towards the light (or the next vertex). Values are per wavelength.
//
// Conventions (pbrt-v4 §9.1, Mitsuba 3):
//   eval(wo, wi)   = f(wo, wi), the BSDF without the cosine factor; 0 for delta lobes.
//   pdf(wo, wi)    = solid-angle density of sample(); 0 for delta lobes.
//   sample(wo,...) = wi ~ pdf, with f; for delta lobes pdf is the discrete lobe probability and
//                    f the delta lobe's coefficient divided by |cos θi| (so f·|cosθi|/pdf is the
//                    path weight in every case).
// One-sided materials (Mitsuba semantics) return 0 when wo.z <= 0; see the twosided wrapper.
#pragma once

#include <cstdint>
#include <optional>

#include "core/frame.h"
#include "spectral/mueller.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

enum class TransportMode { Radiance, Importance };

enum BSDFFlags : uint32_t {
    kBSDFReflection = 1u << 0,
    kBSDFTransmission = 1u << 1,
    kBSDFDiffuse = 1u << 2,
    kBSDFGlossy = 1u << 3,
    kBSDFSpecular = 1u << 4,
    /// Pass-through (Mitsuba's Null lobe, of the `mask`, `null` and `thindielectric` bsdfs): wi = −wo,
    /// the ray goes on unchanged. Sampled together with kBSDFTransmission | kBSDFSpecular (a delta
    /// lobe). The volumetric integrators do not count it as a bounce and let shadow rays cross it
    /// with BSDF::nullTransmission (integrators/volpath.cpp).
    kBSDFNull = 1u << 5,
};

struct BSDFSample {
    SampledSpectrum f;   // BSDF value for the sampled direction (see the file comment)
    vec3 wi{0.0f};       // sampled direction, local frame
    float pdf = 0.0f;    // solid-angle density, or discrete probability for specular lobes
    uint32_t flags = 0;  // the sampled lobe: reflection/transmission × diffuse/glossy/specular
    float eta = 1.0f;    // relative IOR crossed for transmission (for Russian roulette scaling)

    bool isSpecular() const { return flags & kBSDFSpecular; }
    bool isTransmission() const { return flags & kBSDFTransmission; }
    bool isNull() const { return flags & kBSDFNull; }
    /// Path throughput weight f·|cosθi|/pdf.
    SampledSpectrum weight() const { return pdf > 0 ? f * (std::abs(wi.z) / pdf) : SampledSpectrum(f.size()); }
};

/// A sample with the Mueller form M of its f (polarized mode; M(0, 0) is f for an unpolarized
/// lobe); the bases of M are those of BSDF::evalMueller.
struct PolarizedBSDFSample {
    BSDFSample s;
    MuellerSpectrum M;
};

class BSDF {
public:

    virtual SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const = 0;
    /// uc: 1D sample for lobe selection; u: 2D sample for the direction.
    virtual std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const = 0;
    virtual float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const = 0;
    /// Union of the lobes this BSDF has (BSDFFlags).
    virtual uint32_t flags() const = 0;

    bool isSpecularOnly() const {
        const uint32_t f = flags();
        return (f & kBSDFSpecular) && !(f & (kBSDFDiffuse | kBSDFGlossy));
    }
    /// True if next-event estimation can contribute (some non-delta lobe exists).
    bool hasNonSpecular() const { return flags() & (kBSDFDiffuse | kBSDFGlossy); }

    /// The weight a shadow ray keeps when it crosses the surface unchanged, arriving from wo (Mitsuba
    /// 3 BSDF::eval_null_transmission, also Mitsuba 0.6's eval of the ENull component): the
    /// coefficient of the pass-through lobe; nullopt for a BSDF without one (it blocks shadow rays).
    virtual std::optional<SampledSpectrum> nullTransmission(const vec3& wo) const { return (void)wo, std::nullopt; }

    // Polarized mode (docs/polarization.md). f as a Mueller matrix in the local frame, from the
    // Stokes basis of the light arriving, stokesBasis(−wi), to that of the light leaving,
    // stokesBasis(wo) (spectral/stokes_basis.h; Mitsuba 3's pBSDF convention). The defaults are a
    // depolarizer of eval()/sample() and an absorber of nullTransmission(); a polarizing BSDF or a
    // wrapper overrides them.
    virtual MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const {
        return MuellerSpectrum::depolarizer(eval(wo, wi, mode));
    }
    virtual std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const {
        std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        return PolarizedBSDFSample{*s, MuellerSpectrum::depolarizer(s->f)};
    }
    virtual std::optional<MuellerSpectrum> nullTransmissionMueller(const vec3& wo) const {
        std::optional<SampledSpectrum> t = nullTransmission(wo);
        if (!t) return std::nullopt;
        return MuellerSpectrum::absorber(*t);
    }

protected:
    // BSDFs live in the Arena and are never destroyed: the destructor is trivial and non-virtual.
    ~BSDF() = default;

    /// For samplers that choose wi from a mixture of lobes: the sample's pdf and f are this BSDF's
    /// own pdf(wo, wi) and eval(wo, wi) (so sample, pdf and eval agree by construction); no sample
    /// where that pdf is 0.
    std::optional<BSDFSample> sampleFromEval(const vec3& wo, const vec3& wi, uint32_t flags, TransportMode mode) const {
        BSDFSample s;
        s.wi = wi;
        s.pdf = pdf(wo, wi, mode);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, wi, mode);
        s.flags = flags;
        return s;
    }
};

}  // namespace iris
