// The Stokes film of the `stokes` integrator (polarized mode, docs/polarization.md): per pixel the
// mean CIE XYZ of each Stokes component S0..S3 of the light reaching the camera, in the camera's
// reference basis (Mitsuba 3 src/integrators/stokes.cpp: x = ray direction × the sensor's up). Each
// component is a film of its own (render/film.h: exact sums, per-pixel counts), so S0 equals the
// image film and S1..S3 may be negative.
#pragma once

#include <array>

#include "render/film.h"
#include "spectral/mueller.h"
#include "spectral/wavelengths.h"

namespace iris {

class StokesFilm {
public:
    StokesFilm(int width, int height);
    int width() const { return films_[0].width(); }
    int height() const { return films_[0].height(); }
    /// One sample: the XYZ of each component (spectral/xyz.h), times the filter weight; an invalid
    /// estimate (`valid` false) is counted with value 0, as the image film counts it.
    void addSample(int x, int y, const StokesVector& S, const SampledWavelengths& wl, float weight, bool valid);
    /// Component k (0..3) as a film of XYZ values.
    const Film& component(int k) const { return films_[size_t(k)]; }

private:
    std::array<Film, 4> films_;
};

}  // namespace iris
