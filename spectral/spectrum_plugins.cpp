// Spectrum plugins (Mitsuba 3's `<spectrum type="...">` objects, src/spectra/): each registered in
// SpectrumRegistry by its scene-file name and created for the kind of spectrum the parameter is
// (reflectance, unbounded, illuminant). The value forms (`<spectrum value="..."/>`, `<rgb>`,
// `<blackbody>`, a number) stay as they are (spectral/spectrum_params.cpp). Parameter names and
// defaults follow Mitsuba 3's plugins of the same names.
#include "core/xml/xml_values.h"
#include "spectral/mitsuba_rgb.h"
#include "spectral/spectrum_factory.h"
#include "spectral/spectrum_params.h"

namespace iris {

namespace {

/// A comma- or space-separated list of numbers given as a string parameter ("400, 500, 600").
std::vector<float> floatList(const Properties& p, const std::string& name) {
    return parseFloatList(p.getString(name), p.locationOf(name));
}

/// A table with the RGB-mode rule of every tabulated scene spectrum (withSceneTableRGBModeValue).
SpectrumPtr table(const Properties& p, std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind) {
    SpectrumPtr s = withLocation(p.location(), [&] { return makePiecewiseLinearSpectrum(lambdas, values, kind); });
    return withSceneTableRGBModeValue(std::move(s), kind, getConvention(p));
}

/// `uniform`: `value` (default 1) at every wavelength; for an emitter the flat (equal-energy)
/// spectrum as in Mitsuba 3 (RGB mode: its sRGB colour, spectral/mitsuba_rgb.h).
SpectrumPtr createUniform(const Properties& p, SpectrumKind kind) {
    const float v = p.getFloat("value", 1.0f);
    if (kind == SpectrumKind::Illuminant) return mitsuba3UniformEmission(v);
    return std::make_shared<ConstantSpectrum>(v, kind);
}

/// `regular`: `values` at equal steps from `wavelength_min` to `wavelength_max` (nm).
SpectrumPtr createRegular(const Properties& p, SpectrumKind kind) {
    const float lo = p.getFloat("wavelength_min"), hi = p.getFloat("wavelength_max");
    const std::vector<float> values = floatList(p, "values");
    if (values.size() < 2) failAt(p.locationOf("values"), "regular spectrum: at least 2 values needed, got ", values.size());
    if (!(hi > lo)) failAt(p.location(), "regular spectrum: wavelength_max (", hi, ") must exceed wavelength_min (", lo, ")");
    std::vector<float> lambdas(values.size());
    for (size_t i = 0; i < values.size(); ++i) lambdas[i] = lo + (hi - lo) * float(i) / float(values.size() - 1);
    return table(p, std::move(lambdas), values, kind);
}

/// `irregular`: `values` at the given increasing `wavelengths` (nm).
SpectrumPtr createIrregular(const Properties& p, SpectrumKind kind) {
    std::vector<float> lambdas = floatList(p, "wavelengths"), values = floatList(p, "values");
    if (lambdas.size() != values.size())
        failAt(p.location(), "irregular spectrum: ", lambdas.size(), " wavelengths but ", values.size(), " values");
    return table(p, std::move(lambdas), std::move(values), kind);
}

/// `blackbody`: Planck's law at `temperature` (K), normalised as `<blackbody>` is (spectrum_factory.h).
SpectrumPtr createBlackbody(const Properties& p, SpectrumKind) {
    const float t = p.getFloat("temperature");
    if (!(t > 0)) failAt(p.locationOf("temperature"), "blackbody temperature must be positive, got ", t);
    return makeBlackbodySpectrum(t, 1.0f);
}

/// `d65`: CIE illuminant D65 with luminance 1, times `scale` (default 1).
SpectrumPtr createD65(const Properties& p, SpectrumKind) {
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0)) failAt(p.locationOf("scale"), "d65 scale must be non-negative, got ", scale);
    return makeD65Spectrum(scale);
}

/// `srgb`: an RGB `color` upsampled for the parameter's kind, as an `<rgb>` value is.
SpectrumPtr createSrgb(const Properties& p, SpectrumKind kind) {
    p.require("color");
    return makeRGBSpectrum(p.getRGB("color", vec3(0.0f)), kind);
}

}  // namespace

IRIS_REGISTER(SpectrumRegistry, "uniform", createUniform);
IRIS_REGISTER(SpectrumRegistry, "regular", createRegular);
IRIS_REGISTER(SpectrumRegistry, "irregular", createIrregular);
IRIS_REGISTER(SpectrumRegistry, "blackbody", createBlackbody);
IRIS_REGISTER(SpectrumRegistry, "d65", createD65);
IRIS_REGISTER(SpectrumRegistry, "srgb", createSrgb);

}  // namespace iris
