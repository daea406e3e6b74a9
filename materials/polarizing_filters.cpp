// Mitsuba 3's ideal polarizing filters, "polarizer", "retarder" and "circular" (src/bsdfs/
// polarizer.cpp, retarder.cpp, circular.cpp): a forward Dirac lobe (wi = −wo, the pass-through
// lobe kBSDFNull of mask/null, so the volumetric integrators let shadow rays through it) that
// changes only the polarization. Parameters (Mitsuba's):
//   polarizer  theta (degrees, spectrum or texture, 0): rotation of the transmission axis about the
//              beam, the absorbing axis being the surface's v direction (local +y) projected
//              orthogonally to the beam (Korger et al. 2013, "The polarization properties of a
//              tilted polarizer"); transmittance (1); polarizing (true; false: a neutral filter)
//   retarder   theta (degrees, 0): rotation of the fast axis (local +x); delta (degrees, 90): the
//              retardance, times |cos θ| of the incidence (Mitsuba's approximation)
//   circular   transmittance (1); left_handed (false: a right circular polarizer)
// Unpolarized modes see what Mitsuba's unpolarized variants see: the polarizer and the circular
// polarizer transmit half of the light (times transmittance), the retarder all of it.
#include "core/error.h"
#include "core/registry.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "spectral/stokes_basis.h"

namespace iris {
namespace {

constexpr uint32_t kFilterLobe = kBSDFNull | kBSDFTransmission | kBSDFSpecular;
constexpr float kDegrees = kPi / 180.0f;

enum class FilterKind { LinearPolarizer, Retarder, Circular };

struct FilterParams {
    FilterKind kind;
    bool polarizing = true;
    bool leftHanded = false;
};

/// The filter at one surface point: per-lane angles and transmittance.
class FilterBSDF final : public BSDF {
public:
    FilterBSDF(const FilterParams& p, const SampledSpectrum& theta, const SampledSpectrum& delta, const SampledSpectrum& t)
        : p_(p), theta_(theta), delta_(delta), t_(t) {}

    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(t_.size()); }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2&, TransportMode) const override {
        const float c = std::abs(wo.z);
        if (!(c > 0)) return std::nullopt;
        BSDFSample s;
        s.wi = -wo;
        s.pdf = 1.0f;
        s.f = unpolarized() / c;  // f·|cos θi| is the transmitted fraction (materials/bsdf.h)
        s.flags = kFilterLobe;
        return s;
    }
    uint32_t flags() const override { return kFilterLobe; }
    std::optional<SampledSpectrum> nullTransmission(const vec3&) const override { return unpolarized(); }

    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        return PolarizedBSDFSample{*s, mueller(wo) * (1.0f / std::abs(wo.z))};
    }
    std::optional<MuellerSpectrum> nullTransmissionMueller(const vec3& wo) const override { return mueller(wo); }

private:
    SampledSpectrum unpolarized() const { return p_.kind == FilterKind::Retarder ? SampledSpectrum(t_.size(), 1.0f) : t_ * 0.5f; }

    /// The filter's matrix for light travelling along `forward` (local frame), from and to
    /// stokesBasis(forward).
    MuellerSpectrum mueller(const vec3& forward) const {
        const int n = t_.size();
        if (p_.kind == FilterKind::LinearPolarizer && !p_.polarizing) return MuellerSpectrum::absorber(t_ * 0.5f);
        vec3 axis(1, 0, 0);  // the element's x axis (Mitsuba 3 retarder.cpp, circular.cpp)
        if (p_.kind == FilterKind::LinearPolarizer) {
            // Transmission axis: forward × (local +y projected orthogonally to the beam) (Mitsuba 3
            // polarizer.cpp after Korger et al. 2013).
            const vec3 a = glm::normalize(vec3(0, 1, 0) - forward.y * forward);
            axis = glm::cross(forward, a);
        }
        const mueller::BasisRotation r = stokesBasisRotation(forward, axis, stokesBasis(forward));
        MuellerSpectrum M(n);
        for (int i = 0; i < n; ++i) {
            // R M Rᵀ (Mitsuba 3 rotate_mueller_basis_collinear).
            const Mueller4f m = mueller::multiply(mueller::rotator(r), mueller::multiply(element(i, std::abs(forward.z)), transposedRotator(r)));
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) M(a, b)[i] = m.m[a][b];
        }
        return p_.kind == FilterKind::Retarder ? M : M * t_;
    }
    /// The element in its own basis at lane i (Mitsuba 3 mueller.h; rotated by theta with
    /// rotated_element).
    Mueller4f element(int i, float cosTheta) const {
        switch (p_.kind) {
            case FilterKind::LinearPolarizer: return mueller::rotatedElement(theta_[i] * kDegrees, mueller::linearPolarizer(1.0f));
            case FilterKind::Retarder: return mueller::rotatedElement(theta_[i] * kDegrees, mueller::linearRetarder(delta_[i] * kDegrees * cosTheta));
            case FilterKind::Circular: return p_.leftHanded ? mueller::leftCircularPolarizer() : mueller::rightCircularPolarizer();
        }
        return {};
    }
    static Mueller4f transposedRotator(const mueller::BasisRotation& r) { return mueller::rotator({r.c2, -r.s2}); }

    FilterParams p_;
    SampledSpectrum theta_, delta_, t_;
};

class FilterMaterial final : public Material {
public:
    FilterMaterial(const FilterParams& p, SpectrumTexturePtr theta, SpectrumTexturePtr delta, SpectrumTexturePtr t)
        : p_(p), theta_(std::move(theta)), delta_(std::move(delta)), t_(std::move(t)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const int n = wl.size();
        const SampledSpectrum theta = theta_ ? theta_->eval(sp.tex, wl) : SampledSpectrum(n);
        SampledSpectrum delta = delta_ ? delta_->eval(sp.tex, wl) : SampledSpectrum(n);
        return arena.make<FilterBSDF>(p_, theta, delta, t_ ? t_->eval(sp.tex, wl) : SampledSpectrum(n, 1.0f));
    }
    bool transmitsShadowRays() const override { return true; }

private:
    FilterParams p_;
    SpectrumTexturePtr theta_, delta_, t_;
};

std::shared_ptr<Material> createPolarizer(const Properties& p) {
    FilterParams fp{FilterKind::LinearPolarizer};
    fp.polarizing = p.getBool("polarizing", true);
    return std::make_shared<FilterMaterial>(fp, getSpectrumTexture(p, "theta", SpectrumKind::Unbounded, 0.0f), nullptr,
                                            getSpectrumTexture(p, "transmittance", SpectrumKind::Reflectance, 1.0f));
}

std::shared_ptr<Material> createRetarder(const Properties& p) {
    return std::make_shared<FilterMaterial>(FilterParams{FilterKind::Retarder}, getSpectrumTexture(p, "theta", SpectrumKind::Unbounded, 0.0f),
                                            getSpectrumTexture(p, "delta", SpectrumKind::Unbounded, 90.0f), nullptr);
}

std::shared_ptr<Material> createCircular(const Properties& p) {
    FilterParams fp{FilterKind::Circular};
    fp.leftHanded = p.getBool("left_handed", false);
    return std::make_shared<FilterMaterial>(fp, nullptr, nullptr, getSpectrumTexture(p, "transmittance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "polarizer", createPolarizer);
IRIS_REGISTER(MaterialRegistry, "retarder", createRetarder);
IRIS_REGISTER(MaterialRegistry, "circular", createCircular);

}  // namespace iris
