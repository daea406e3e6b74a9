// Spectral upsampling for many RGB values (bitmap textures, environment maps): instead of one
// sigmoid fit per distinct colour (≈ 150 µs each, spectral/rgb_spectrum.h), reflectance spectra are
// fitted once at the nodes of a regular grid over [0,1]³ and a colour's spectrum is the trilinear
// interpolation of its cell's 8 node spectra. The RGB projection (spectral/color_space.h) is linear
// in the spectrum and trilinear weights reproduce any linear function of the node positions, so the
// interpolated spectrum projects back onto the colour up to the nodes' own fit error (exact for
// non-grey nodes to float precision; 1.7e-4 relative for greys, the IEC matrix residual); it stays
// in [0,1] (a convex combination of reflectances). The grid is built lazily on first use
// (thread-safe), never at start-up.
#pragma once

#include <vector>

#include "spectral/rgb_spectrum.h"

namespace iris {

class RGBSpectrumGrid {
public:
    static constexpr int kResolution = 17;  // nodes per axis (spacing 1/16)

    /// The process-wide grid, built on the first call.
    static const RGBSpectrumGrid& instance();
    /// True once instance() has built the grid (for tests and diagnostics).
    static bool built();

    /// Reflectance spectrum of rgb (clamped to [0,1]³) at the wavelengths (spectral mode).
    SampledSpectrum reflectance(const vec3& rgb, const SampledWavelengths& wl) const;
    /// The same at one wavelength (nm).
    float reflectance(const vec3& rgb, float lambda) const;
    /// makeRGBSpectrum's conventions for every kind (Unbounded m·s(rgb/m); Illuminant
    /// m·s(rgb/m)·D65 with Y(D65) = 1), the shape s coming from the grid. RGB mode: rgb unchanged.
    SampledSpectrum sample(const vec3& rgb, SpectrumKind kind, const SampledWavelengths& wl) const;

private:
    struct Cell {
        const RGBSpectrum* node[8];
        float weight[8];
    };
    RGBSpectrumGrid();
    Cell cell(const vec3& rgb) const;
    std::vector<RGBSpectrum> nodes_;  // index (r·K + g)·K + b
};

}  // namespace iris
