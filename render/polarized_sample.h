// One camera sample of a polarized render (docs/polarization.md): the integrator's Stokes estimate
// along the ray. The image receives S0 (the radiance an ordinary camera measures); the `stokes`
// integrator estimates all four components, which go to the Stokes film.
#pragma once

#include "render/integrator.h"

namespace iris {

/// S0 of the ray's Stokes estimate; `all`, if given, receives S0..S3 (S1..S3 are zero unless the
/// integrator estimates them, as `stokes` does).
SampledSpectrum polarizedSample(const Integrator& integrator, const Scene& scene, const Ray& ray, SampledWavelengths& wl,
                                Sampler& sampler, Arena& arena, PathStats& stats, StokesVector* all);

/// True for an estimate the film may take: S0 finite and non-negative, S1..S3 finite.
bool validStokes(const StokesVector& S);

}  // namespace iris
