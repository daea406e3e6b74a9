#include "spectral/ior_params.h"

#include <cmath>
#include <cstdlib>
#include <utility>

#include "core/error.h"
#include "spectral/ior_presets.h"
#include "spectral/mitsuba_rgb.h"
#include "spectral/spectrum_params.h"

namespace iris {

namespace {

/// The parameters of the dispersion formulas of `name` (see ior_params.h).
struct FormulaNames {
    std::string base, cauchyA, cauchyB, sellmeierB, sellmeierC;
    explicit FormulaNames(const std::string& name)
        : base(name.size() > 4 && name.compare(name.size() - 4, 4, "_ior") == 0 ? name.substr(0, name.size() - 4) : name),
          cauchyA(base + "_cauchy_a"),
          cauchyB(base + "_cauchy_b"),
          sellmeierB(base + "_sellmeier_b"),
          sellmeierC(base + "_sellmeier_c") {}
};

IOR fromText(const Properties& p, const std::string& name, const std::string& text, const SourceLocation& loc) {
    float eta;
    if (lookupIORPreset(text, &eta)) return IOR::constant(eta);
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    if (!text.empty() && end && *end == '\0') return IOR::constant(v);
    failAt(loc, p.type(), ": parameter '", name, "': unknown IOR preset '", text, "' (known: ", iorPresetList(), ")");
}

bool tripleValue(const PropertyValue& v, vec3* out) {
    if (const RGBValue* c = std::get_if<RGBValue>(&v)) *out = c->rgb;
    else if (const VectorValue* w = std::get_if<VectorValue>(&v)) *out = w->v;
    else if (const PointValue* q = std::get_if<PointValue>(&v)) *out = q->v;
    else return false;
    return true;
}

/// What one call reads: a parameter, its default and quantity, the material's channel wavelengths
/// (nullptr: `<name>_wavelengths`).
struct IorParam {
    const std::string& name;
    const IOR& def;
    IorQuantity quantity;
    const vec3* channelLambdas;
};

/// `param.name`'s value, by its type; *perChannel is set for the rgb form.
IOR fromValue(const Properties& p, const IorParam& param, bool* perChannel) {
    const Properties::Entry& e = *p.find(param.name);
    const bool index = param.quantity == IorQuantity::Index;
    if (const float* f = std::get_if<float>(&e.value)) return IOR::constant(*f);
    if (const int64_t* i = std::get_if<int64_t>(&e.value)) return IOR::constant(float(*i));
    if (const std::string* s = std::get_if<std::string>(&e.value); s && index) return fromText(p, param.name, *s, e.loc);
    vec3 rgb;
    if (param.quantity != IorQuantity::ConductorOptics && tripleValue(e.value, &rgb)) {
        *perChannel = true;
        const vec3 lambdas = param.channelLambdas ? *param.channelLambdas
                                                  : p.getVector(param.name + "_wavelengths", defaultChannelWavelengths());
        return IOR::perChannel(rgb, lambdas);
    }
    if (std::holds_alternative<SpectrumValue>(e.value) || std::holds_alternative<RGBValue>(e.value)) {
        SpectrumPtr s = getSpectrum(p, param.name, SpectrumKind::Unbounded);
        if (const auto* c = dynamic_cast<const ConstantSpectrum*>(s.get())) return IOR::constant(c->value());
        // Mitsuba's conductor eta/k given as a table: RGB mode renders with the RGB value Mitsuba's
        // RGB variant of the value's convention computes (spectral/mitsuba_rgb.h), not the table at the
        // channel wavelengths.
        if (const auto* table = std::get_if<SpectrumValue>(&e.value); table && param.quantity == IorQuantity::ConductorOptics)
            s = withMitsubaRGBModeValue(std::move(s), MitsubaTableSource::SceneValue, table->convention);
        return IOR::tabulated(std::move(s));
    }
    p.typeError(param.name, index ? "index of refraction (float, IOR preset name, rgb or spectrum)"
                                  : "float, rgb or spectrum");
}

/// The one validity check of every index read: finite, and > 0 (an index) or ≥ 0 (κ, conductor
/// optics), at every value the IOR takes (IOR::forEachValue).
void checkValues(const Properties& p, const std::string& name, IorQuantity q, const IOR& ior) {
    const bool zeroAllowed = q != IorQuantity::Index;
    ior.forEachValue([&](float lambda, float v) {
        if (std::isfinite(v) && (zeroAllowed ? v >= 0 : v > 0)) return;
        failAt(p.locationOf(name), p.type(), ": parameter '", name, "' must be finite and ",
               zeroAllowed ? ">= 0 (extinction coefficients and conductor constants are non-negative)"
                           : "> 0 (indices of refraction are positive)",
               " at every wavelength, got ", v, " at ", lambda, " nm");
    });
}

IOR readParam(const Properties& p, const IorParam& param) {
    const FormulaNames f(param.name);
    const bool formulas = param.quantity == IorQuantity::Index;
    const bool cauchy = formulas && (p.present(f.cauchyA) || p.present(f.cauchyB));
    const bool sellmeier = formulas && (p.present(f.sellmeierB) || p.present(f.sellmeierC));
    const bool value = p.present(param.name);
    if (int(value) + int(cauchy) + int(sellmeier) > 1)
        failAt(p.location(), p.tag(), " '", p.type(), "': give only one of ", param.name, ", ", f.base, "_cauchy_*, ",
               f.base, "_sellmeier_*");
    bool perChannel = false;
    const IOR ior = cauchy      ? IOR::cauchy(p.getFloat(f.cauchyA), p.getFloat(f.cauchyB, 0.0f))
                    : sellmeier ? IOR::sellmeier(p.getVector(f.sellmeierB), p.getVector(f.sellmeierC))
                    : value     ? fromValue(p, param, &perChannel)
                                : param.def;
    const std::string wavelengths = param.name + "_wavelengths";
    if (!param.channelLambdas && !perChannel && p.present(wavelengths))
        failAt(p.locationOf(wavelengths), "parameter '", wavelengths, "' only applies to an rgb ", param.name);
    checkValues(p, cauchy ? f.cauchyA : sellmeier ? f.sellmeierB : param.name, param.quantity, ior);
    return ior;
}

}  // namespace

IOR readIOR(const Properties& p, const std::string& name, const IOR& def, IorQuantity quantity) {
    return readParam(p, {name, def, quantity, nullptr});
}

IOR readIOR(const Properties& p, const std::string& name, const IOR& def, const vec3& channelLambdas) {
    return readParam(p, {name, def, IorQuantity::Index, &channelLambdas});
}

float readConstantIOR(const Properties& p, const std::string& name, float def) {
    const IOR ior = readIOR(p, name, IOR::constant(def));
    if (ior.isDispersive())
        failAt(p.locationOf(name), p.type(), ": parameter '", name,
               "' must be one index (a float or a preset name), not one that varies with wavelength");
    return ior.eval(kLambdaMin);
}

InterfaceIOR readInterfaceIOR(const Properties& p) {
    return {readIOR(p, "int_ior", presetIOR("bk7")), readIOR(p, "ext_ior", presetIOR("air"))};
}

bool iorGiven(const Properties& p, const std::string& name) {
    const FormulaNames f(name);
    return p.has(name) || p.has(f.cauchyA) || p.has(f.cauchyB) || p.has(f.sellmeierB) || p.has(f.sellmeierC);
}

}  // namespace iris
