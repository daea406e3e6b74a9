#include "render/polarized_sample.h"

namespace iris {

SampledSpectrum polarizedSample(const Integrator& integrator, const Scene& scene, const Ray& ray, SampledWavelengths& wl,
                                Sampler& sampler, Arena& arena, PathStats& stats, StokesVector* all) {
    StokesEstimate est;
    est.S = StokesVector(wl.size());
    integrator.LiStokes(scene, ray, wl, sampler, arena, stats, est);
    if (all) *all = est.S;
    return est.S.s[0];
}

bool validStokes(const StokesVector& S) {
    if (S.s[0].hasNegative()) return false;
    for (const SampledSpectrum& c : S.s)
        if (c.hasNonFinite()) return false;
    return true;
}

}  // namespace iris
