// The SGGX specular microflake phase function (Mitsuba 3 `sggx`, src/phase/sggx.cpp; Heitz et al.
// 2015, sggx_math.h). Light arriving from wo (pointing away from the point) is mirrored by a
// microflake of normal m into wi = 2(wo·m)m − wo; with the half vector m = (wo + wi)/|wo + wi|
//   p(wo, wi) = D(m) / (4 σ(wo))         (Heitz et al. 2015, supp. §2.4, the specular microflake phase function)
// which integrates to 1 over wi, and is reciprocal with σ: σ(wo) p(wo, wi) = σ(wi) p(wi, wo).
// Sampling draws m from the visible normals of wo and mirrors wo (exact: pdf = p). S = I (a sphere
// of flakes) gives isotropic scattering, 1/(4π).
//
// Parameters, as Mitsuba 3: `S`, a <volume> of 6 channels (S_xx, S_yy, S_zz, S_xy, S_xz, S_yz,
// world-space entries; a gridvolume, whose trilinear interpolation keeps S positive definite) —
// or, an iris shorthand for a constant S, the six floats `S_xx`, `S_yy`, `S_zz` (default 1) and
// `S_xy`, `S_xz`, `S_yz` (default 0). S must be positive definite: a constant is checked, and
// every voxel of a grid (a located error naming the voxel). Mitsuba 3 leaves this to the user.
// As in Mitsuba 3's volpath, a medium's extinction does not depend on direction (the microflakes'
// projected area σ(ω) only shapes the phase function), and the diffuse SGGX variant is absent.
#include <array>
#include <string>

#include "core/error.h"
#include "core/io/vol_reader.h"
#include "media/phase/phase_function.h"
#include "media/phase/sggx_math.h"
#include "media/volumes/volume.h"

namespace iris {
namespace {

constexpr std::array<const char*, 6> kEntryNames = {"S_xx", "S_yy", "S_zz", "S_xy", "S_xz", "S_yz"};

class SggxPhase final : public PhaseFunction {
public:
    SggxPhase(VolumePtr grid, const SggxMatrix& constant) : grid_(std::move(grid)), constant_(constant) {}

    float eval(const vec3& x, const vec3& wo, const vec3& wi) const override { return float(value(at(x), wo, wi)); }
    float pdf(const vec3& x, const vec3& wo, const vec3& wi) const override { return float(value(at(x), wo, wi)); }
    std::optional<PhaseSample> sample(const vec3& x, const vec3& wo, const vec2& u) const override {
        const SggxMatrix S = at(x);
        const dvec3 m = sggxSampleVisibleNormal(S, wo, u);
        const dvec3 wi = glm::normalize(2.0 * glm::dot(dvec3(wo), m) * m - dvec3(wo));
        const float p = float(sggxD(S, m) / (4.0 * sggxProjectedArea(S, dvec3(wo))));
        if (!(p > 0)) return std::nullopt;
        return PhaseSample{vec3(wi), p, p};
    }

private:
    SggxMatrix at(const vec3& x) const {
        if (!grid_) return constant_;
        float c[6];
        grid_->evalChannels(x, c);
        return SggxMatrix::fromChannels(c);
    }
    /// D(m) / (4 σ(wo)) at the half vector m of wo and wi; 0 for wi = −wo (m undefined).
    static double value(const SggxMatrix& S, const vec3& wo, const vec3& wi) {
        const dvec3 h = dvec3(wo) + dvec3(wi);
        const double len = glm::length(h);
        if (!(len > 1e-9)) return 0.0;
        return sggxD(S, h / len) / (4.0 * sggxProjectedArea(S, dvec3(wo)));
    }

    VolumePtr grid_;
    SggxMatrix constant_;
};

/// Every voxel of a 6-channel grid must be positive definite (then so is every trilinear mix).
void checkGrid(const Properties& p, const Volume& v) {
    const VolumeGridData* g = v.grid();
    if (!g) return;
    for (int z = 0; z < g->zres; ++z)
        for (int y = 0; y < g->yres; ++y)
            for (int x = 0; x < g->xres; ++x)
                if (!SggxMatrix::fromChannels(&g->values[g->index(x, y, z, 0)]).positiveDefinite())
                    failAt(p.locationOf("S"), "sggx: S is not positive definite at voxel (", x, ", ", y, ", ", z, ") of the grid");
}

SggxMatrix readConstant(const Properties& p) {
    double e[6];
    for (int i = 0; i < 6; ++i) e[i] = p.getFloat(kEntryNames[size_t(i)], i < 3 ? 1.0f : 0.0f);
    const SggxMatrix S{e[0], e[1], e[2], e[3], e[4], e[5]};
    if (!S.positiveDefinite())
        failAt(p.location(), "sggx: the matrix S_xx..S_yz = (", e[0], ", ", e[1], ", ", e[2], ", ", e[3], ", ", e[4], ", ", e[5],
               ") is not positive definite");
    return S;
}

std::shared_ptr<PhaseFunction> createSggx(const Properties& p) {
    if (!p.present("S")) return std::make_shared<SggxPhase>(nullptr, readConstant(p));
    for (const char* name : kEntryNames)
        if (p.present(name)) failAt(p.locationOf(name), "sggx: give either the volume S or the six floats S_xx..S_yz, not both");
    VolumePtr grid = getChannelVolume(p, "S", 6);
    checkGrid(p, *grid);
    return std::make_shared<SggxPhase>(std::move(grid), SggxMatrix{});
}

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "sggx", createSggx);

}  // namespace iris
