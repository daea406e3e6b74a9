#include "spectral/dispersion.h"

#include <cstdlib>
#include <utility>

#include "core/error.h"
#include "spectral/spectrum_params.h"

namespace iris {

IOR IOR::constant(float eta) {
    IOR r;
    r.kind_ = Kind::Constant;
    r.c_ = eta;
    return r;
}
IOR IOR::cauchy(float a, float bUm2) {
    IOR r;
    r.kind_ = Kind::Cauchy;
    r.a_ = vec3(a, bUm2, 0);
    return r;
}
IOR IOR::sellmeier(const vec3& b, const vec3& cUm2) {
    IOR r;
    r.kind_ = Kind::Sellmeier;
    r.a_ = b;
    r.b_ = cUm2;
    return r;
}
IOR IOR::tabulated(SpectrumPtr spectrum) {
    if (!spectrum) fail("IOR::tabulated: null spectrum");
    IOR r;
    r.kind_ = Kind::Tabulated;
    r.spectrum_ = std::move(spectrum);
    return r;
}
IOR IOR::perChannel(const vec3& eta, const vec3& lambdas) {
    IOR r;
    r.kind_ = Kind::PerChannel;
    r.a_ = eta;
    r.b_ = lambdas;
    return r;
}

float IOR::eval(float lambda) const {
    switch (kind_) {
        case Kind::Constant: return c_;
        case Kind::Cauchy: {
            const float l = lambda * 1e-3f;  // µm
            return a_.x + a_.y / (l * l);    // Cauchy: η = A + B/λ²
        }
        case Kind::Sellmeier: {
            const float l2 = sqr(lambda * 1e-3f);  // µm²
            // Sellmeier: η² = 1 + Σ B_i λ²/(λ² − C_i)
            float n2 = 1.0f;
            for (int i = 0; i < 3; ++i) n2 += a_[i] * l2 / (l2 - b_[i]);
            return safeSqrt(n2);
        }
        case Kind::Tabulated: return spectrum_->eval(lambda);
        case Kind::PerChannel: {
            // Piecewise linear through the three (λ, η) points sorted by λ, constant outside.
            std::pair<float, float> pts[3] = {{b_.x, a_.x}, {b_.y, a_.y}, {b_.z, a_.z}};
            std::sort(std::begin(pts), std::end(pts));
            if (lambda <= pts[0].first) return pts[0].second;
            if (lambda >= pts[2].first) return pts[2].second;
            for (int i = 0; i < 2; ++i) {
                if (lambda <= pts[i + 1].first) {
                    const float span = pts[i + 1].first - pts[i].first;
                    const float t = span > 0 ? (lambda - pts[i].first) / span : 0.0f;
                    return lerp(t, pts[i].second, pts[i + 1].second);
                }
            }
            return pts[2].second;
        }
    }
    return 1.0f;
}

SampledSpectrum IOR::sample(const SampledWavelengths& wl) const {
    if (kind_ == Kind::Constant) return SampledSpectrum(wl.size(), c_);  // = eval at every λ, without the switch
    SampledSpectrum s(wl.size());
    if (wl.isRGB() && kind_ == Kind::PerChannel) {
        for (int i = 0; i < 3; ++i) s[i] = a_[i];
        return s;
    }
    for (int i = 0; i < wl.size(); ++i) s[i] = eval(wl.lambda(i));
    return s;
}

bool IOR::isDispersive() const {
    switch (kind_) {
        case Kind::Constant: return false;
        case Kind::Cauchy: return a_.y != 0.0f;
        case Kind::Sellmeier: return true;
        case Kind::Tabulated: return true;
        case Kind::PerChannel: return !(a_.x == a_.y && a_.y == a_.z);
    }
    return false;
}

namespace {
// Mitsuba 3 dielectric plugin documentation, table "Refractive index presets" (values at 589 nm
// from standard references, as listed there).
const std::pair<const char*, float> kPresets[] = {
    {"vacuum", 1.0f},           {"helium", 1.00004f},       {"hydrogen", 1.00013f},
    {"air", 1.000277f},         {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
    {"acetone", 1.36f},         {"ethanol", 1.361f},        {"carbon tetrachloride", 1.461f},
    {"glycerol", 1.4729f},      {"benzene", 1.501f},        {"silicone oil", 1.52045f},
    {"bromine", 1.661f},        {"water ice", 1.31f},       {"fused quartz", 1.458f},
    {"pyrex", 1.470f},          {"acrylic glass", 1.49f},   {"polypropylene", 1.49f},
    {"bk7", 1.5046f},           {"sodium chloride", 1.544f}, {"amber", 1.55f},
    {"pet", 1.5750f},           {"diamond", 2.419f},
};
}  // namespace

bool lookupIORPreset(const std::string& name, float* eta) {
    for (const auto& [n, v] : kPresets) {
        if (name == n) {
            *eta = v;
            return true;
        }
    }
    return false;
}

std::vector<std::string> iorPresetNames() {
    std::vector<std::string> names;
    for (const auto& [n, v] : kPresets) names.emplace_back(n);
    return names;
}

namespace {
IOR iorFromText(const std::string& text, const SourceLocation& loc, const std::string& param) {
    float eta;
    if (lookupIORPreset(text, &eta)) return IOR::constant(eta);
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    if (end && *end == '\0' && !text.empty()) return IOR::constant(v);
    std::string list;
    for (const auto& n : iorPresetNames()) list += (list.empty() ? "" : ", ") + n;
    failAt(loc, "parameter '", param, "': unknown IOR preset '", text, "' (known: ", list, ")");
}
}  // namespace

IOR readIOR(const Properties& p, const std::string& prefix, const std::string& def) {
    const std::string iorName = prefix + "_ior", wlName = prefix + "_ior_wavelengths";
    const std::string ca = prefix + "_cauchy_a", cb = prefix + "_cauchy_b";
    const std::string sb = prefix + "_sellmeier_b", sc = prefix + "_sellmeier_c";
    const int forms = int(p.has(iorName)) + int(p.has(ca) || p.has(cb)) + int(p.has(sb) || p.has(sc));
    if (forms > 1)
        failAt(p.location(), p.tag(), " '", p.type(), "': give only one of ", iorName, ", ", prefix, "_cauchy_*, ",
               prefix, "_sellmeier_*");
    IOR result;
    if (p.has(ca) || p.has(cb)) {
        result = IOR::cauchy(p.getFloat(ca), p.getFloat(cb, 0.0f));
    } else if (p.has(sb) || p.has(sc)) {
        result = IOR::sellmeier(p.getVector(sb), p.getVector(sc));
    } else if (p.has(iorName)) {
        const SourceLocation loc = p.locationOf(iorName);
        // The value's type decides the form; each getter throws on a type mismatch.
        bool done = false;
        try {
            result = IOR::constant(p.getFloat(iorName));
            done = true;
        } catch (const Error&) {
        }
        if (!done) {
            try {
                const std::string s = p.getString(iorName);
                result = iorFromText(s, loc, iorName);
                done = true;
            } catch (const Error& e) {
                if (std::string(e.what()).find("unknown IOR preset") != std::string::npos) throw;
            }
        }
        if (!done) {
            try {
                // rgb (or a vector): per-channel values.
                result = IOR::perChannel(p.getRGB(iorName, vec3(1.0f)), p.getVector(wlName, vec3(645, 525, 445)));
                done = true;
            } catch (const Error&) {
            }
        }
        if (!done) {
            try {
                SpectrumPtr spec = getSpectrum(p, iorName, SpectrumKind::Unbounded);
                if (const auto* c = dynamic_cast<const ConstantSpectrum*>(spec.get()))
                    result = IOR::constant(c->value());
                else
                    result = IOR::tabulated(std::move(spec));
                done = true;
            } catch (const Error& e) {
                failAt(loc, "parameter '", iorName, "' must be a float, a preset name, an rgb triple or a spectrum (",
                       e.what(), ")");
            }
        }
    } else {
        result = iorFromText(def, p.location(), iorName);
    }
    if (p.has(wlName) && result.kind() != IOR::Kind::PerChannel)
        failAt(p.locationOf(wlName), "parameter '", wlName, "' only applies to an rgb ", iorName);
    if (p.has(wlName)) p.getVector(wlName);  // mark as used
    return result;
}


float relativeIOR(const IOR& intIOR, const IOR& extIOR, SampledWavelengths& wl, SampledSpectrum* eta) {
    *eta = intIOR.sample(wl) / extIOR.sample(wl);
    const bool varies = [&] {
        for (int i = 1; i < eta->size(); ++i)
            if ((*eta)[i] != (*eta)[0]) return true;
        return false;
    }();
    if (wl.isRGB()) return (*eta)[1];
    if (varies) wl.terminateSecondary();
    return (*eta)[0];
}

}  // namespace iris
