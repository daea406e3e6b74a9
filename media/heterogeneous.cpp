// The `heterogeneous` medium (Mitsuba 3 src/media/heterogeneous.cpp): `sigma_t` (float, spectrum
// or <volume>; default 1) and `albedo` (float, spectrum or <volume>; default 0.75), `scale`
// (float, default 1), `has_spectral_extinction` (accepted, no effect: a Mitsuba sampling choice),
// plus readMediumCommon's nested <phase> and `sample_emitters`.
//   σ_t(p) = scale · sigma_t(p),   σ_s(p) = σ_t(p) · albedo(p)      (get_scattering_coefficients)
// The medium fills the world box of its sigma_t volume only (Mitsuba 3 intersect_aabb returns
// m_sigmat->bbox(), and Medium::sample_interaction clips the ray to it): σ_t = 0 outside; inside,
// the volumes are evaluated with their wrap modes (a rotated to_world's box holds points outside
// the local unit cube). A constant sigma_t (a constvolume: a number or spectrum given directly
// is one, as in Mitsuba 3 Properties::volume) fills to_world's unit cube, [0,1]³ by default.
// Majorants: a constant sigma_t gives one segment over the box with σ_maj = σ_t per lane (no null
// collisions); a grid gives one segment per majorant-grid cell (media/majorant_grid.h),
// σ_maj = scale · the cell's bound.
#include <cmath>

#include "media/majorant_grid.h"
#include "media/medium.h"
#include "media/volumes/volume.h"

namespace iris {
namespace {

class HeterogeneousMedium final : public Medium {
public:
    HeterogeneousMedium(MediumCommon common, VolumePtr sigmaT, VolumePtr albedo, float scale)
        : Medium(std::move(common.phase), common.sampleEmitters, std::move(common.emission)), sigmaT_(std::move(sigmaT)),
          albedo_(std::move(albedo)), scale_(scale),
          grid_(*sigmaT_, sigmaT_->isConstant() ? ivec3(1) : MajorantGrid::resolutionFor(*sigmaT_)) {}

    MediumCoefficients coefficients(const vec3& p, const SampledWavelengths& wl) const override {
        if (!sigmaT_->bounds().contains(p)) return {SampledSpectrum(wl.size()), SampledSpectrum(wl.size())};
        const SampledSpectrum sigmaT = scale_ * sigmaT_->eval(p, wl);
        return {sigmaT * albedo_->eval(p, wl), sigmaT};
    }

    MajorantIterator* majorants(const Ray& ray, float tMax, const SampledWavelengths& wl, Arena& arena) const override {
        if (!sigmaT_->isConstant()) return grid_.traverse(ray, tMax, scale_, wl.size(), arena);
        float t0 = 0.0f, t1 = 0.0f;
        const Box3& box = sigmaT_->bounds();
        const SampledSpectrum sigma = scale_ * sigmaT_->eval(box.lo, wl);  // exact: σ_maj = σ_t
        if (box.degenerate() || sigma.isBlack() || !box.clip(ray, tMax, t0, t1)) t0 = t1 = 0.0f;
        return arena.make<ConstantMajorantIterator>(t0, t1, sigma);
    }

private:
    VolumePtr sigmaT_, albedo_;
    float scale_;
    MajorantGrid grid_;
};

float readScale(const Properties& p) {
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0.0f) || !std::isfinite(scale))
        failAt(p.locationOf("scale"), "heterogeneous: scale must be a finite number >= 0, not ", scale);
    return scale;
}

VolumePtr readSigmaT(const Properties& p) {
    VolumePtr v = getVolume(p, "sigma_t", SpectrumKind::Unbounded, 1.0f);
    if (v->range().min < 0.0f)
        failAt(p.locationOf("sigma_t"), "heterogeneous: sigma_t has negative values (minimum ", v->range().min,
               "); extinction must be >= 0");
    return v;
}

VolumePtr readAlbedo(const Properties& p) {
    VolumePtr v = getVolume(p, "albedo", SpectrumKind::Reflectance, 0.75f);
    const ValueRange r = v->range();
    if (r.min < 0.0f || r.max > 1.0f)
        failAt(p.locationOf("albedo"), "heterogeneous: albedo must lie in [0, 1], its values range over [", r.min, ", ",
               r.max, "]");
    return v;
}

std::shared_ptr<Medium> create(const Properties& p) {
    MediumCommon common = readMediumCommon(p);
    const float scale = readScale(p);
    VolumePtr sigmaT = readSigmaT(p);
    VolumePtr albedo = readAlbedo(p);
    p.getBool("has_spectral_extinction", true);  // Mitsuba 3: which channel drives sampling; no effect here
    return std::make_shared<HeterogeneousMedium>(std::move(common), std::move(sigmaT), std::move(albedo), scale);
}

}  // namespace

IRIS_REGISTER(MediumRegistry, "heterogeneous", create);

}  // namespace iris
