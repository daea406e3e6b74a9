#include "render/stokes_film.h"

#include "spectral/xyz.h"

namespace iris {

StokesFilm::StokesFilm(int width, int height)
    : films_{Film(width, height), Film(width, height), Film(width, height), Film(width, height)} {}

void StokesFilm::addSample(int x, int y, const StokesVector& S, const SampledWavelengths& wl, float weight, bool valid) {
    for (int k = 0; k < 4; ++k) {
        const vec3 xyz = valid ? toXYZ(S.s[k], wl) : vec3(0.0f);  // toXYZ is linear: signed S1..S3 are fine
        films_[size_t(k)].addSample(x, y, weight == 1.0f ? xyz : weight * xyz);
    }
}

}  // namespace iris
