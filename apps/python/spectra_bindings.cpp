// Spectra and colour from Python: the CIE 1931 tables and D65 (spectral/cie.h), spectrum → XYZ
// by the renderer's own 1 nm quadrature (spectral/xyz.h, integrateXYZ), colour-space conversion
// and display transforms through OpenColorIO (spectral/color_management.h), and RGB → spectrum
// upsampling (Jakob & Hanika 2019, spectral/rgb_upsampling.h).
#include <cmath>
#include <memory>

#include "apps/python/bindings.h"
#include "spectral/cie.h"
#include "spectral/color_management.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/rgb_upsampling.h"
#include "spectral/wavelengths.h"
#include "spectral/xyz.h"

namespace iris::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// f applied to every entry of a 1D float array.
template <typename F>
py::array_t<float> mapLambdas(const py::array& lambdas, F&& f) {
    const FloatArray l = inputArray<float>(lambdas, "wavelengths_nm", 1);
    std::vector<float> out(size_t(l.size()));
    for (py::ssize_t i = 0; i < l.size(); ++i) {
        if (!std::isfinite(l.data()[i])) fail("wavelengths_nm[", i, "] is ", l.data()[i], " (expected a finite number)");
        out[size_t(i)] = f(l.data()[i]);
    }
    return ownedArray(std::move(out), {l.size()});
}

py::array_t<float> xyzBar(const py::array& lambdas) {
    const FloatArray l = inputArray<float>(lambdas, "wavelengths_nm", 1);
    std::vector<float> out(size_t(3 * l.size()));
    for (py::ssize_t i = 0; i < l.size(); ++i) {
        if (!std::isfinite(l.data()[i])) fail("wavelengths_nm[", i, "] is ", l.data()[i], " (expected a finite number)");
        const vec3 c = cie::xyzBar(l.data()[i]);
        for (int k = 0; k < 3; ++k) out[size_t(3 * i + k)] = c[k];
    }
    return ownedArray(std::move(out), {l.size(), 3});
}

/// XYZ of a tabulated spectrum (piecewise linear, constant outside its table, as the renderer
/// reads <spectrum value="λ:v, ..."/>), by the 1 nm quadrature normalised by ∫ȳ.
py::array_t<double> spectrumToXYZ(const py::array& lambdas, const py::array& values) {
    const FloatArray l = inputArray<float>(lambdas, "wavelengths_nm", 1), v = inputArray<float>(values, "values", 1);
    if (l.size() != v.size()) fail("wavelengths_nm and values must have the same length (", l.size(), " and ", v.size(), ")");
    const PiecewiseLinearSpectrum s(std::vector<float>(l.data(), l.data() + l.size()),
                                    std::vector<float>(v.data(), v.data() + v.size()), SpectrumKind::Unbounded);
    const dvec3 xyz = integrateXYZ([&](float lambda) { return s.eval(lambda); });
    return ownedArray(std::vector<double>{xyz.x, xyz.y, xyz.z}, {3});
}

/// A colour manager per config path, created once (loading an OCIO config is not free).
const ColorManager& colorManager(const std::string& config) {
    static std::map<std::string, std::unique_ptr<ColorManager>> cache;
    auto& slot = cache[config];
    if (!slot) slot = std::make_unique<ColorManager>(config);
    return *slot;
}

/// (…, 3) float32 pixels converted (a copy; the input is not modified).
py::array_t<float> convertColors(const py::array& rgb, const std::string& from, const std::string& to,
                                 const std::string& config, bool display, const std::string& view) {
    const ColorManager& cm = colorManager(config);
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(rgb);
    if (!a || a.ndim() < 1 || a.shape(a.ndim() - 1) != 3) fail("colors: expected an array whose last dimension is 3");
    if (!cm.hasColorSpace(from)) fail("colour space '", from, "' is not in ", cm.configPath());
    if (!display && !cm.hasColorSpace(to)) fail("colour space '", to, "' is not in ", cm.configPath());
    std::vector<float> out(a.data(), a.data() + a.size());
    std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
    const size_t pixels = out.size() / 3;
    {
        py::gil_scoped_release release;
        if (display)
            cm.toDisplay(out.data(), pixels, from, to, view);
        else
            cm.convert(out.data(), pixels, from, to);
    }
    return ownedArray(std::move(out), shape);
}

vec3 toVec3(const std::vector<float>& v, const char* name) {
    if (v.size() != 3) fail(name, ": expected 3 values, got ", v.size());
    for (float x : v)
        if (!std::isfinite(x)) fail(name, ": ", x, " is not a finite number");
    return vec3(v[0], v[1], v[2]);
}

}  // namespace

void bindSpectra(py::module_& m) {
    m.def("cie_xyz_bar", &xyzBar, py::arg("wavelengths_nm"));
    m.def("cie_d65", [](const py::array& l) { return mapLambdas(l, [](float x) { return cie::d65(x); }); }, py::arg("wavelengths_nm"));
    m.def("cie_y_integral", &cie::yIntegral);
    m.def("visible_wavelength_pdf", [](const py::array& l) { return mapLambdas(l, [](float x) { return visibleWavelengthPdf(x); }); },
          py::arg("wavelengths_nm"));
    m.def("spectrum_to_xyz", &spectrumToXYZ, py::arg("wavelengths_nm"), py::arg("values"));
    m.def("convert_colors", &convertColors, py::arg("colors"), py::arg("source"), py::arg("target"), py::arg("config"),
          py::arg("display"), py::arg("view"));
    m.def("color_spaces", [](const std::string& config) { return colorManager(config).colorSpaces(); }, py::arg("config"));
    m.def("ocio_config_path", [](const std::string& config) { return colorManager(config).configPath(); }, py::arg("config"));
    m.def("fit_rgb", [](const std::vector<float>& rgb) {
        const SigmoidFit fit = fitSigmoidPolynomial(toVec3(rgb, "rgb"));
        return py::make_tuple(std::vector<float>{fit.poly.c0, fit.poly.c1, fit.poly.c2}, fit.error, fit.iterations);
    }, py::arg("rgb"));
    m.def("eval_sigmoid", [](const std::vector<float>& c, const py::array& l) {
        const vec3 v = toVec3(c, "coefficients");
        const SigmoidPolynomial s{v.x, v.y, v.z};
        return mapLambdas(l, [&](float x) { return s(x); });
    }, py::arg("coefficients"), py::arg("wavelengths_nm"));
    m.def("sigmoid_rgb", [](const std::vector<float>& c) {
        const vec3 v = toVec3(c, "coefficients");
        const vec3 rgb = reflectanceRGB(SigmoidPolynomial{v.x, v.y, v.z});
        return std::vector<float>{rgb.x, rgb.y, rgb.z};
    }, py::arg("coefficients"));
    m.attr("LAMBDA_MIN") = kLambdaMin;
    m.attr("LAMBDA_MAX") = kLambdaMax;
    const vec3 l = defaultChannelWavelengths();
    m.attr("DEFAULT_RGB_WAVELENGTHS") = py::make_tuple(l.x, l.y, l.z);
}

}  // namespace iris::python
