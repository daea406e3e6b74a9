#include "spectral/spectrum_params.h"

#include "spectral/mitsuba_rgb.h"
#include "spectral/spectrum_factory.h"

namespace iris {

SpectrumPtr spectrumFromValue(const SpectrumValue& v, SpectrumKind kind, const SourceLocation& loc) {
    // File errors already name their file; withLocation adds where the scene asked for it.
    return withLocation(loc, [&]() -> SpectrumPtr {
        switch (v.type) {
            case SpectrumValue::Type::Constant:  // <spectrum value="0.3"/>: a number, like <float> (0.x rule)
                return spectrumFromNumber(v.constant, kind);
            case SpectrumValue::Type::Pairs:
                return makePiecewiseLinearSpectrum(v.lambdas, v.values, kind);
            case SpectrumValue::Type::File:
                return loadSpdFile(v.path, kind);
            case SpectrumValue::Type::Blackbody:
                return makeBlackbodySpectrum(v.temperature, v.scale);
        }
        fail("invalid spectrum value");
    });
}

SpectrumPtr withSceneTableRGBModeValue(SpectrumPtr spec, SpectrumKind kind, MitsubaConvention convention) {
    if (kind == SpectrumKind::Unbounded) return spec;
    return withMitsubaRGBModeValue(std::move(spec), MitsubaTableSource::SceneValue, convention);
}

/// A plain number as a spectrum, given as <float> (or as a single-valued <spectrum> in a version 0.x
/// scene). Emitters multiply it by D65 with Y = 1 (Mitsuba 3 for a number: `d65` / `srgb` (v, v, v);
/// Mitsuba 0.6 for both forms, intent "illuminant"; issue 14 item 7), so it renders the same white,
/// (v, v, v), in spectral and RGB mode.
SpectrumPtr spectrumFromNumber(float v, SpectrumKind kind) {
    if (kind == SpectrumKind::Illuminant) return makeRGBSpectrum(vec3(v), kind);
    return std::make_shared<ConstantSpectrum>(v, kind);
}

SpectrumPtr getSpectrum(const Properties& p, const std::string& name, SpectrumKind kind) {
    const Properties::Entry& e = p.require(name);
    if (const float* f = std::get_if<float>(&e.value)) return spectrumFromNumber(*f, kind);
    if (const int64_t* i = std::get_if<int64_t>(&e.value)) return spectrumFromNumber(float(*i), kind);
    if (const RGBValue* c = std::get_if<RGBValue>(&e.value)) return makeRGBSpectrum(c->rgb, kind);
    if (const PropertiesPtr* obj = std::get_if<PropertiesPtr>(&e.value); obj && (*obj)->tag() == "spectrum")
        return SpectrumRegistry::instance().create(**obj, kind);
    if (const SpectrumValue* s = std::get_if<SpectrumValue>(&e.value)) {
        // An emitter's single-valued <spectrum>: Mitsuba 3's flat spectrum (RGB mode: its sRGB
        // colour). A version 0.x scene's has become a number (value × D65, spectrumFromNumber) in
        // the upgrade pass (render/loader/scene_upgrade.h).
        if (s->type == SpectrumValue::Type::Constant && kind == SpectrumKind::Illuminant)
            return mitsuba3UniformEmission(s->constant);
        return withSceneTableRGBModeValue(spectrumFromValue(*s, kind, e.loc), kind, s->convention);
    }
    p.typeError(name, "spectrum (float, rgb, spectrum or blackbody value, or a <spectrum type=...> object)");
}
SpectrumPtr getSpectrum(const Properties& p, const std::string& name, SpectrumKind kind, float def) {
    return p.present(name) ? getSpectrum(p, name, kind) : spectrumFromNumber(def, kind);
}

}  // namespace iris
