// What a polarized render asks of an integrator for one camera ray (docs/polarization.md): the
// Stokes vector of the light arriving at the camera along the ray, S0 only (the image of
// `--mode polarized`) or S0..S3 (the `stokes` integrator), in a reference basis the caller names.
#pragma once

#include "core/math.h"
#include "spectral/mueller.h"

namespace iris {

struct StokesEstimate {
    /// 1: only S0 is estimated (it does not depend on the basis); 4: S0..S3.
    int rows = 1;
    /// The reference basis vector x of the measured Stokes vector (unit, orthogonal to the ray;
    /// the light travels along −ray.d). Ignored when rows = 1.
    vec3 basis{1, 0, 0};
    /// The estimate per wavelength (S1..S3 stay zero when rows = 1).
    StokesVector S;
};

}  // namespace iris
