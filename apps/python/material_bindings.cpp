// Materials from Python: any registered BSDF (materials/material.h, MaterialRegistry) created from
// a <bsdf> XML fragment (the package also turns dicts into fragments), evaluated at arrays of
// local-frame directions (normal +z, both directions pointing away from the surface; materials/bsdf.h)
// for chosen wavelengths in spectral mode or the three channels of RGB mode.
#include <algorithm>
#include <cmath>

#include "apps/python/bindings.h"
#include "core/arena.h"
#include "core/xml/xml_parser.h"
#include "materials/material.h"
#include "materials/textures/texture.h"
#include "spectral/wavelengths.h"

namespace iris::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// Which wavelengths a query uses: RGB mode's three channels, or spectral mode at given λ.
struct WavelengthSet {
    bool rgb = false;
    vec3 rgbLambdas = defaultChannelWavelengths();
    std::vector<float> lambdas;  // spectral mode
    int count() const { return rgb ? 3 : int(lambdas.size()); }
    /// Groups of at most kMaxWavelengths, each one SampledWavelengths (one BSDF per group).
    std::vector<SampledWavelengths> groups() const {
        if (rgb) return {SampledWavelengths::rgb(rgbLambdas)};
        std::vector<SampledWavelengths> g;
        for (size_t i = 0; i < lambdas.size(); i += kMaxWavelengths)
            g.push_back(SampledWavelengths::fixed(lambdas.data() + i, int(std::min<size_t>(kMaxWavelengths, lambdas.size() - i))));
        return g;
    }
};

WavelengthSet wavelengthSet(const py::object& lambdas, const std::vector<float>& rgbLambdas) {
    WavelengthSet w;
    if (lambdas.is_none()) {
        w.rgb = true;
        if (!rgbLambdas.empty()) w.rgbLambdas = vec3(rgbLambdas[0], rgbLambdas[1], rgbLambdas[2]);
        return w;
    }
    const FloatArray l = inputArray<float>(lambdas, "wavelengths_nm", 1);
    if (l.shape(0) < 1) fail("wavelengths_nm: give at least one wavelength");
    w.lambdas.assign(l.data(), l.data() + l.size());
    return w;
}

/// Directions (n, 3): finite, non-zero; normalised here (the BSDF interface expects unit vectors).
std::vector<vec3> directions(const py::array& a, const char* name) {
    const FloatArray d = inputArray<float>(a, name, 2, 3);
    std::vector<vec3> v(size_t(d.shape(0)));
    for (py::ssize_t i = 0; i < d.shape(0); ++i) {
        const vec3 x(d.data()[3 * i], d.data()[3 * i + 1], d.data()[3 * i + 2]);
        const float len = glm::length(x);
        if (!std::isfinite(len) || len == 0.0f) fail(name, "[", i, "] = (", x.x, ", ", x.y, ", ", x.z, ") is not a direction (zero, NaN or infinite)");
        v[size_t(i)] = x / len;
    }
    return v;
}

TransportMode transportMode(const std::string& t) {
    if (t == "radiance") return TransportMode::Radiance;
    if (t == "importance") return TransportMode::Importance;
    fail("transport: unknown '", t, "' (expected radiance or importance)");
}

/// A material and the BSDF it gives at the surface point of the default ShadingPoint (uv = 0).
class PyMaterial {
public:
    PyMaterial(const std::string& xml, const std::string& baseDir) {
        // The fragment starts on the wrapper's line, so messages name the fragment's own lines.
        const ParsedScene parsed = parseSceneString("<scene version=\"3.0.0\">" + xml + "\n</scene>", baseDir);
        if (parsed.objects.size() != 1 || parsed.objects[0]->tag() != "bsdf")
            fail("<string>: expected exactly one <bsdf> element, got ", parsed.objects.size(), " top-level objects");
        type_ = parsed.objects[0]->type();
        material_ = MaterialRegistry::instance().create(*parsed.objects[0]);
    }
    const std::string& type() const { return type_; }

    py::array_t<float> eval(const py::array& woIn, const py::array& wiIn, const WavelengthSet& w, TransportMode mode) const {
        const std::vector<vec3> wo = directions(woIn, "wo"), wi = directions(wiIn, "wi");
        if (wo.size() != wi.size()) fail("wo and wi must hold the same number of directions (", wo.size(), " and ", wi.size(), ")");
        const size_t n = wo.size(), m = size_t(w.count());
        std::vector<float> out(n * m, 0.0f);
        py::gil_scoped_release release;
        size_t offset = 0;
        for (SampledWavelengths& wl : w.groups()) {
            Arena arena;
            if (const BSDF* b = material_->getBSDF(ShadingPoint{}, wl, arena))
                for (size_t i = 0; i < n; ++i) {
                    const SampledSpectrum f = b->eval(wo[i], wi[i], mode);
                    for (int k = 0; k < wl.size(); ++k) out[i * m + offset + size_t(k)] = f[k];
                }
            offset += size_t(wl.size());
        }
        return ownedArray(std::move(out), {py::ssize_t(n), py::ssize_t(m)});
    }

    /// pdf of the first wavelength group's BSDF (directions are chosen with the hero wavelength).
    py::array_t<float> pdf(const py::array& woIn, const py::array& wiIn, const WavelengthSet& w, TransportMode mode) const {
        const std::vector<vec3> wo = directions(woIn, "wo"), wi = directions(wiIn, "wi");
        if (wo.size() != wi.size()) fail("wo and wi must hold the same number of directions (", wo.size(), " and ", wi.size(), ")");
        std::vector<float> out(wo.size(), 0.0f);
        py::gil_scoped_release release;
        SampledWavelengths wl = w.groups()[0];
        Arena arena;
        if (const BSDF* b = material_->getBSDF(ShadingPoint{}, wl, arena))
            for (size_t i = 0; i < wo.size(); ++i) out[i] = b->pdf(wo[i], wi[i], mode);
        return ownedArray(std::move(out), {py::ssize_t(wo.size())});
    }

    py::dict sample(const py::array& woIn, const py::array& ucIn, const py::array& uIn, const WavelengthSet& w,
                    TransportMode mode) const {
        if (w.count() > kMaxWavelengths) fail("sample: at most ", kMaxWavelengths, " wavelengths per call, got ", w.count());
        const std::vector<vec3> wo = directions(woIn, "wo");
        const FloatArray uc = inputArray<float>(ucIn, "uc", 1), u = inputArray<float>(uIn, "u", 2, 2);
        const size_t n = wo.size(), m = size_t(w.count());
        if (size_t(uc.shape(0)) != n || size_t(u.shape(0)) != n) fail("wo, uc and u must have the same length");
        for (size_t i = 0; i < n; ++i)
            for (float x : {uc.data()[i], u.data()[2 * i], u.data()[2 * i + 1]})
                if (!(x >= 0.0f && x < 1.0f)) fail("sample numbers uc and u must lie in [0, 1), got ", x, " at entry ", i);
        std::vector<float> wi(3 * n, 0.0f), f(n * m, 0.0f), pdf(n, 0.0f), eta(n, 1.0f);
        std::vector<uint32_t> flags(n, 0);
        std::vector<uint8_t> valid(n, 0);
        {
            py::gil_scoped_release release;
            SampledWavelengths wl = w.groups()[0];
            Arena arena;
            if (const BSDF* b = material_->getBSDF(ShadingPoint{}, wl, arena))
                for (size_t i = 0; i < n; ++i) {
                    const auto s = b->sample(wo[i], uc.data()[i], vec2(u.data()[2 * i], u.data()[2 * i + 1]), mode);
                    if (!s) continue;
                    valid[i] = 1;
                    for (int c = 0; c < 3; ++c) wi[3 * i + c] = s->wi[c];
                    for (size_t k = 0; k < m; ++k) f[i * m + k] = s->f[int(k)];
                    pdf[i] = s->pdf;
                    flags[i] = s->flags;
                    eta[i] = s->eta;
                }
        }
        py::dict d;
        const py::ssize_t pn = py::ssize_t(n);
        d["wi"] = ownedArray(std::move(wi), {pn, 3});
        d["f"] = ownedArray(std::move(f), {pn, py::ssize_t(m)});
        d["pdf"] = ownedArray(std::move(pdf), {pn});
        d["flags"] = ownedArray(std::move(flags), {pn});
        d["eta"] = ownedArray(std::move(eta), {pn});
        d["valid"] = ownedArray(std::move(valid), {pn}).attr("astype")("bool");
        return d;
    }

    uint32_t flags(const WavelengthSet& w) const {
        SampledWavelengths wl = w.groups()[0];
        Arena arena;
        const BSDF* b = material_->getBSDF(ShadingPoint{}, wl, arena);
        return b ? b->flags() : 0u;
    }

private:
    std::string type_;
    MaterialPtr material_;
};

}  // namespace

void bindMaterials(py::module_& m) {
    py::class_<PyMaterial>(m, "Material")
        .def(py::init<const std::string&, const std::string&>(), py::arg("xml"), py::arg("base_dir"))
        .def_property_readonly("type", &PyMaterial::type)
        .def("eval", [](const PyMaterial& self, const py::array& wo, const py::array& wi, const py::object& lambdas,
                        const std::vector<float>& rgbLambdas, const std::string& transport) {
            return self.eval(wo, wi, wavelengthSet(lambdas, rgbLambdas), transportMode(transport));
        }, py::arg("wo"), py::arg("wi"), py::arg("wavelengths_nm"), py::arg("rgb_wavelengths"), py::arg("transport"))
        .def("pdf", [](const PyMaterial& self, const py::array& wo, const py::array& wi, const py::object& lambdas,
                       const std::vector<float>& rgbLambdas, const std::string& transport) {
            return self.pdf(wo, wi, wavelengthSet(lambdas, rgbLambdas), transportMode(transport));
        }, py::arg("wo"), py::arg("wi"), py::arg("wavelengths_nm"), py::arg("rgb_wavelengths"), py::arg("transport"))
        .def("sample", [](const PyMaterial& self, const py::array& wo, const py::array& uc, const py::array& u,
                          const py::object& lambdas, const std::vector<float>& rgbLambdas, const std::string& transport) {
            return self.sample(wo, uc, u, wavelengthSet(lambdas, rgbLambdas), transportMode(transport));
        }, py::arg("wo"), py::arg("uc"), py::arg("u"), py::arg("wavelengths_nm"), py::arg("rgb_wavelengths"), py::arg("transport"))
        .def("flags", [](const PyMaterial& self, const py::object& lambdas, const std::vector<float>& rgbLambdas) {
            return self.flags(wavelengthSet(lambdas, rgbLambdas));
        }, py::arg("wavelengths_nm"), py::arg("rgb_wavelengths"));
    m.def("material_types", [] { return MaterialRegistry::instance().names(); });
    m.def("texture_types", [] {
        std::vector<std::string> names = SpectrumTextureRegistry::instance().names();
        for (const auto& n : FloatTextureRegistry::instance().names())
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
        return names;
    });
    m.attr("BSDF_REFLECTION") = uint32_t(kBSDFReflection);
    m.attr("BSDF_TRANSMISSION") = uint32_t(kBSDFTransmission);
    m.attr("BSDF_DIFFUSE") = uint32_t(kBSDFDiffuse);
    m.attr("BSDF_GLOSSY") = uint32_t(kBSDFGlossy);
    m.attr("BSDF_SPECULAR") = uint32_t(kBSDFSpecular);
    m.attr("BSDF_NULL") = uint32_t(kBSDFNull);
}

}  // namespace iris::python
