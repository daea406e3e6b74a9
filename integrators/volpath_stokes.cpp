#include "integrators/volpath_stokes.h"

#include "spectral/stokes_basis.h"

namespace iris {

VertexMueller surfaceMueller(const BSDF& bsdf, const Frame& frame, const vec3& woLocal, const vec3& wiLocal) {
    VertexMueller v;
    v.M = bsdf.evalMueller(woLocal, wiLocal, TransportMode::Radiance) * std::abs(wiLocal.z);
    v.wi = frame.toWorld(wiLocal);
    v.inBasis = frame.toWorld(stokesBasis(-wiLocal));
    v.outBasis = frame.toWorld(stokesBasis(woLocal));
    return v;
}

VertexMueller phaseMueller(const PhaseFunction& phase, const vec3& x, const vec3& wo, const vec3& wi, int n) {
    return {phase.evalMueller(x, wo, wi, n), wi, stokesBasis(-wi), stokesBasis(wo)};
}

ShadowMueller::ShadowMueller(int n, const vec3& shadowDir)
    : M_(MuellerSpectrum::absorber(SampledSpectrum(n, 1.0f))), forward_(-shadowDir), basis_(stokesBasis(-shadowDir)) {}

ShadowMueller ShadowMueller::zero(int n, const vec3& shadowDir) {
    ShadowMueller s(n, shadowDir);
    s.M_ = MuellerSpectrum::depolarizer(SampledSpectrum(n));
    return s;
}

void ShadowMueller::cross(const MuellerSpectrum& local, const Frame& f) {
    // The crossing's basis, stokesBasis of the local direction of travel, rotated to this one's:
    // R M Rᵀ (Mitsuba 3 rotate_mueller_basis_collinear); nearer the light means applied first.
    const vec3 current = f.toWorld(stokesBasis(f.toLocal(forward_)));
    const mueller::BasisRotation r = stokesBasisRotation(forward_, current, basis_);
    M_ = M_ * mueller::rotateBases(local, r, r);
}

StokesVector ShadowMueller::arriving(const SampledSpectrum& L) const { return M_ * StokesVector::unpolarized(L); }

void addLightThrough(const StokesThroughput& rows, const VertexMueller& v, const ShadowMueller& shadow, const SampledSpectrum& L,
                     float w, StokesVector& est) {
    // The light's Stokes vector re-expressed in the vertex's input basis (it travels along −wi).
    StokesVector s = shadow.arriving(L);
    const mueller::BasisRotation r = stokesBasisRotation(-v.wi, shadow.basis(), v.inBasis);
    const SampledSpectrum s1 = s.s[1], s2 = s.s[2];
    s.s[1] = s1 * r.c2 + s2 * r.s2;  // rotator · S (Collett ch. 5 eq. 43)
    s.s[2] = s2 * r.c2 - s1 * r.s2;
    const StokesVector out = v.M * s;
    for (int k = 0; k < rows.rows(); ++k) {
        SampledSpectrum c = rows.at(k, 0) * out.s[0];
        for (int j = 1; j < 4; ++j) c += rows.at(k, j) * out.s[j];
        est.s[k] += c * w;
    }
}

}  // namespace iris
