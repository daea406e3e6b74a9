// A thin-film coating as materials use it: the scene-level description (indices as IORs,
// spectral/ior.h; thickness texture, extra layers, substrate, phase mode) and its per-path
// instance with the complex indices at the path's wavelengths, which evaluates the exact stack
// reflectance / transmittance (spectral/thin_film_stack.h) at any angle. Parameters: docs/thin_film.md.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/arena.h"
#include "core/properties.h"
#include "materials/textures/texture.h"
#include "spectral/thin_film_airy_batch.h"
#include "spectral/thin_film_polarization.h"
#include "spectral/thin_film_stack.h"
#include "spectral/ior.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

struct AiryAngle;  // spectral/thin_film_airy.h

enum class ThinFilmSubstrate { Conductor, Dielectric };
enum class ThinFilmRGBMode { Point, BelcourBarla, Cycles42 };

/// Scene-level description of a coating (shared by thinfilm and iridescent_diffuse).
struct ThinFilmCoatingSpec {
    float extIor = 1.0f;  // incident (exterior) medium, real
    IOR filmIor = IOR::constant(1.5f), filmK = IOR::constant(0.0f);
    FloatTexturePtr thickness;  // nm
    struct ExtraLayer {
        IOR ior, k;
        float thicknessNm = 0;
    };
    std::vector<ExtraLayer> extra;  // below the film, top → bottom
    IOR substrateEta = IOR::constant(1.5f), substrateK = IOR::constant(0.0f);
    ThinFilmPhaseMode mode = ThinFilmPhaseMode::Exact;
    int bounces = 1;
    ThinFilmRGBMode rgbMode = ThinFilmRGBMode::Point;

    /// Cache of the hemispherical internal reflectance (ThinFilmCoating::internalHemisphericalReflectance)
    /// for a constant thickness: spectral mode reads r_int(λ) from a table at kRintStep nm over
    /// [360, 830] (linear interpolation), RGB mode with the given channel wavelengths reads rgb.
    struct RintCache {
        static constexpr float kStep = 0.5f;
        std::vector<float> table;  // λ = 360 + i·kStep
        vec3 rgbLambdas{0.0f}, rgb{0.0f};
    };
    std::shared_ptr<const RintCache> rintCache;
    /// Fill rintCache (only when the thickness is a constant texture; otherwise a no-op).
    void precomputeInternalReflectance(const vec3& rgbLambdas = defaultChannelWavelengths());

    /// Read the coating parameters (film_ior, film_k, thickness, layerN_ior/_k/_thickness,
    /// phase_mode, bounces, rgb_mode, ext_ior) and the substrate's (by default substrate_eta,
    /// substrate_k with the given defaults). Every index is read by spectral/ior_params.h (the
    /// indices with IorQuantity::Index, the `_k` with Extinction). Throws a located iris::Error
    /// on invalid values. `etaName`/`kName` name the substrate's parameters (kName = nullptr: a
    /// real substrate, k = 0, e.g. etaName "int_ior"). With a kName, `substrate_material` may
    /// instead name a conductor preset (conductor_presets.h).
    static ThinFilmCoatingSpec fromProperties(const Properties& p, float defSubstrateEta, float defSubstrateK,
                                          float defThickness = 300.0f, const char* etaName = "substrate_eta",
                                          const char* kName = "substrate_k");
};

/// The arguments of ThinFilmCoating's per-path constructor, so that a BSDF can build its coating member
/// in place (ThinFilmCoating is over 1 KB: a temporary plus a copy per shading point is avoidable).
struct ThinFilmCoatingArgs {
    const ThinFilmCoatingSpec& spec;
    const TextureQuery& tex;
    const SampledWavelengths& wl;
    Arena& arena;
};

/// Per-path instance: indices at the path's wavelengths. Trivially destructible (arena).
class ThinFilmCoating {
public:
    /// Evaluate the spec at a surface point for wavelengths wl (extra layers go to the arena).
    ThinFilmCoating(const ThinFilmCoatingSpec& spec, const TextureQuery& q, const SampledWavelengths& wl, Arena& arena);
    /// Spectral-mode instance at explicit wavelengths (n ≤ kMaxWavelengths), for precomputation.
    ThinFilmCoating(const ThinFilmCoatingSpec& spec, const TextureQuery& q, const float* lambdas, int n, Arena& arena);

    int size() const { return n_; }
    double thicknessNm() const { return thickness_; }

    /// Reflectance of the stack for light from the exterior at cosθ (to the interface normal), per
    /// entry: RGB Belcour–Barla mode → spectrally integrated RGB; RGB Cycles 4.2 mode → channel k of
    /// spectral/thin_film_cycles.h with entry k's indices; otherwise the exact / truncated /
    /// incoherent stack at each wavelength (truncated sums clamped to [0, 1]).
    SampledSpectrum reflectance(float cosTheta) const;
    /// Reflectance and transmittance (into the substrate) at each wavelength. Belcour–Barla mode
    /// over a non-absorbing substrate: the integrated R and T = 1 − R (the film is lossless there);
    /// over an absorbing one, point values. Cycles 4.2 mode (non-absorbing substrate only): its R
    /// and T = 1 − R.
    void reflectanceTransmittance(float cosTheta, SampledSpectrum& R, SampledSpectrum& T) const;
    /// The stack lit from the substrate side (substrate must be a real dielectric medium): light
    /// in the substrate at cosθ towards the film, exiting into the exterior medium.
    void fromBelowRT(float cosTheta, SampledSpectrum& R, SampledSpectrum& T) const;
    /// Stack result at entry k (exterior side).
    ThinFilmStackResult stackRT(int k, double cosTheta) const;
    ThinFilmStackResult stackRTFromBelow(int k, double cosTheta) const;

    /// Hemispherical (cosine-weighted) reflectance of the stack lit from the substrate side,
    /// r_int = 2 ∫_0^1 R_below(μ) μ dμ, at entry k: Gauss–Legendre quadrature (16 nodes) on each side of
    /// the critical cosine μc = sqrt(1 − (n_ext/n_sub)²), where R jumps to total reflection (above μc
    /// with μ = μc + (1 − μc) t² to remove the square-root edge).
    /// Uses the spec's RintCache when it applies (constant thickness; RGB: same channel wavelengths).
    double internalHemisphericalReflectance(int k) const;
    /// Always the quadrature (for tests of the cache).
    double internalHemisphericalReflectanceDirect(int k) const;

    /// Polarized mode (docs/polarization.md): the s and p powers and the cross terms of the stack's
    /// Mueller matrices at entry k, for light at cosθ from the exterior or (below) the substrate;
    /// the powers equal stackRT / stackRTFromBelow's (materials/thin_film_coating_polarized.cpp).
    FilmPolarization polarization(int k, double cosTheta, bool below = false) const;
    /// polarization(k, cosTheta, below).power without the cross terms: stackRT / stackRTFromBelow.
    ThinFilmStackResult polarizationPowers(int k, double cosTheta, bool below = false) const;
    /// Every entry's polarization terms, structure of arrays (entry k at index k; left
    /// uninitialised: a vertex fills one per evaluation).
    struct PolarizationLanes {
        alignas(32) double Rs[kMaxWavelengths], Rp[kMaxWavelengths], Ts[kMaxWavelengths], Tp[kMaxWavelengths];
        alignas(32) double crossRRe[kMaxWavelengths], crossRIm[kMaxWavelengths], crossTRe[kMaxWavelengths],
            crossTIm[kMaxWavelengths];
    };
    /// polarization at every entry k < size() at once (polarizationPowersAll: polarizationPowers,
    /// the powers only): an exact single film through the batched kernel
    /// (spectral/thin_film_airy_batch.h), whose lanes agree with the per-entry forms to rounding
    /// (relative 1e-14), other stacks and declined entries entry by entry.
    void polarizationAll(double cosTheta, bool below, PolarizationLanes& out) const;
    void polarizationPowersAll(double cosTheta, bool below, PolarizationLanes& out) const;

    double extIor() const { return extIor_; }
    complexd substrateIor(int k) const { return substrate_[k]; }

private:
    ThinFilmStackResult exactAt(int k, double cosTheta, bool below, const AiryAngle& angle) const;
    ThinFilmStackResult exactFallback(int k, double cosTheta, bool below) const;  // transfer matrix
    /// Builds the Airy arrays or the layer rows from lambda_, film_, substrate_ (set by the
    /// constructors); extraIor(j, k) is the complex index of extra layer j at entry k.
    template <typename ExtraIorAt>
    void init(const ThinFilmCoatingSpec& spec, Arena& arena, ExtraIorAt&& extraIor);

    int n_ = 0, nExtra_ = 0, bounces_ = 1;
    ThinFilmPhaseMode mode_ = ThinFilmPhaseMode::Exact;
    bool belcourBarla_ = false;
    bool cycles42_ = false;  // RGB mode with rgb_mode "cycles_4_2"
    double extIor_ = 1.0, thickness_ = 0.0;
    double lambda_[kMaxWavelengths];
    complexd film_[kMaxWavelengths];
    complexd substrate_[kMaxWavelengths];
    Layer* layers_ = nullptr;  // per entry k: layers_[k·(1+nExtra) + j], j = 0 the film
    /// Exact mode with a single film: the angle-independent Airy constants per entry (arena,
    /// structure of arrays padded to kAiryLanes for spectral/thin_film_airy_batch.h), hoisted out of every
    /// evaluation; nullptr otherwise. Arrays: film ñ1² (re, im), 1/ñ1² (re, im), k0 d, substrate ñ2²
    /// (re, im), 1/ñ2² (re, im), and the exterior's ñ0², 1/ñ0² repeated (the substrate of the
    /// reversed stack, fromBelow).
    enum AiryArray { kN1Re, kN1Im, kInv1Re, kInv1Im, kK0d, kN2Re, kN2Im, kInv2Re, kInv2Im,
                     kExtRe, kExtIm, kExtInvRe, kExtInvIm, kAiryArrays };
    const double* airy_ = nullptr;
    int airyStride_ = 0;  // padded entry count: array a starts at airy_ + a·airyStride_
    const double* airyArray(AiryArray a) const { return airy_ + a * airyStride_; }
    /// The hoisted Airy constants of entry k: the film's, and the substrate's (the exterior's when
    /// lit from below: the four substrate arrays follow each other).
    AiryFilmConstants airyFilm(int k) const {
        return {complexd(airyArray(kN1Re)[k], airyArray(kN1Im)[k]), complexd(airyArray(kInv1Re)[k], airyArray(kInv1Im)[k]),
                airyArray(kK0d)[k]};
    }
    SquaredIndex airySubstrate(int k, bool below) const {
        const int sub = below ? kExtRe : kN2Re;
        return {complexd(airyArray(AiryArray(sub))[k], airyArray(AiryArray(sub + 1))[k]),
                complexd(airyArray(AiryArray(sub + 2))[k], airyArray(AiryArray(sub + 3))[k])};
    }
    /// The s and p powers at every entry through the batched kernel (airy_ set), the entries it
    /// declines by the transfer matrix (exactFallback): exactAt's values except T ≤ 1 − R.
    void exactPowersAll(double cosTheta, bool below, double* Rs, double* Rp, double* Ts, double* Tp) const;
    /// R and T at every entry through the batched kernel (airy_ set, not Belcour–Barla).
    void exactAll(double cosTheta, bool below, SampledSpectrum& R, SampledSpectrum* T) const;
    /// The batched kernel's s and p powers at every entry (airy_ set): out's R, T arrays (and the
    /// cross terms when out asks for them, AiryBatchOutput); returns the entries it declined.
    uint32_t airyBatch(double cosTheta, bool below, const AiryBatchOutput& out) const;
    const ThinFilmCoatingSpec::RintCache* rint_ = nullptr;  // set when the cache applies to these wavelengths
    bool rgb_ = false;
};

}  // namespace iris
