// The industry's thin-film approximations from Python (spectral/thin_film_industry.h,
// spectral/thin_film_cycles.h): the KHR_materials_iridescence RGB Fresnel as its README writes it,
// Blender Cycles 4.2's thin film as its source writes it, and Gulbrandsen 2014's metal index. The package (iris/film.py) broadcasts the inputs to flat arrays of one length n.
#include <cmath>

#include "apps/python/bindings.h"
#include "metrics/color_difference.h"
#include "spectral/thin_film_cycles.h"
#include "spectral/thin_film_industry.h"

namespace iris::python {

namespace {

using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

void checkPositive(const RealArray& a, const char* name, bool allowZero) {
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        const double v = a.data()[i];
        if (!std::isfinite(v) || v < 0 || (!allowZero && v == 0)) fail(name, "[", i, "] = ", v, allowZero ? " (expected >= 0)" : " (expected > 0)");
    }
}

/// (n, 3) KHR_materials_iridescence iridescent_fresnel for base F0 (n, 3).
py::array_t<double> khrRgb(const py::array& cosTheta, const py::array& outsideIor, const py::array& filmIor, const py::array& thickness,
                           const py::array& baseF0) {
    const RealArray c = inputArray<double>(cosTheta, "cos_theta", 1), n0 = inputArray<double>(outsideIor, "outside_ior", 1);
    const RealArray eta = inputArray<double>(filmIor, "film_ior", 1), d = inputArray<double>(thickness, "thickness_nm", 1);
    const RealArray f0 = inputArray<double>(baseF0, "base_f0", 2, 3);
    const py::ssize_t n = c.shape(0);
    if (n0.shape(0) != n || eta.shape(0) != n || d.shape(0) != n || f0.shape(0) != n) fail("the inputs must have the same length");
    checkPositive(n0, "outside_ior", false), checkPositive(eta, "film_ior", false), checkPositive(d, "thickness_nm", true);
    for (py::ssize_t i = 0; i < n; ++i) {
        if (!(c.data()[i] >= 0 && c.data()[i] <= 1)) fail("cos_theta[", i, "] = ", c.data()[i], " (expected in [0, 1])");
        for (int k = 0; k < 3; ++k)
            if (!(f0.data()[3 * i + k] >= 0 && f0.data()[3 * i + k] < 1)) fail("base_f0[", i, "] must lie in [0, 1)");
    }
    std::vector<double> out(size_t(3 * n));
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const dvec3 F = khrIridescentFresnel(n0.data()[i], eta.data()[i], dvec3(f0.data()[3 * i], f0.data()[3 * i + 1], f0.data()[3 * i + 2]),
                                                 d.data()[i], c.data()[i]);
            for (int k = 0; k < 3; ++k) out[size_t(3 * i + k)] = F[k];
        }
    }
    return ownedArray(std::move(out), {n, 3});
}

/// (n, 3) Blender Cycles 4.2's thin-film Fresnel over a dielectric base of real index base_ior.
py::array_t<double> cyclesRgb(const py::array& cosTheta, const py::array& outsideIor, const py::array& filmIor, const py::array& thickness,
                              const py::array& baseIor) {
    const RealArray c = inputArray<double>(cosTheta, "cos_theta", 1), n0 = inputArray<double>(outsideIor, "outside_ior", 1);
    const RealArray eta = inputArray<double>(filmIor, "film_ior", 1), d = inputArray<double>(thickness, "thickness_nm", 1);
    const RealArray base = inputArray<double>(baseIor, "base_ior", 1);
    const py::ssize_t n = c.shape(0);
    if (n0.shape(0) != n || eta.shape(0) != n || d.shape(0) != n || base.shape(0) != n) fail("the inputs must have the same length");
    checkPositive(n0, "outside_ior", false), checkPositive(eta, "film_ior", false), checkPositive(d, "thickness_nm", true);
    checkPositive(base, "base_ior", false);
    for (py::ssize_t i = 0; i < n; ++i)
        if (!(c.data()[i] >= 0 && c.data()[i] <= 1)) fail("cos_theta[", i, "] = ", c.data()[i], " (expected in [0, 1])");
    std::vector<double> out(size_t(3 * n));
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const dvec3 F = cyclesThinFilmRGB(n0.data()[i], eta.data()[i], base.data()[i], c.data()[i], d.data()[i]);
            for (int k = 0; k < 3; ++k) out[size_t(3 * i + k)] = F[k];
        }
    }
    return ownedArray(std::move(out), {n, 3});
}

/// (n,) complex indices of Gulbrandsen 2014 for reflectivity r and edge tint g.
py::array_t<complexd> gulbrandsen(const py::array& r, const py::array& g) {
    const RealArray rr = inputArray<double>(r, "reflectivity", 1), gg = inputArray<double>(g, "edge_tint", 1);
    if (rr.shape(0) != gg.shape(0)) fail("reflectivity and edge_tint must have the same length");
    std::vector<complexd> out(size_t(rr.shape(0)));
    for (py::ssize_t i = 0; i < rr.shape(0); ++i) {
        if (!(rr.data()[i] >= 0 && rr.data()[i] <= 1)) fail("reflectivity[", i, "] = ", rr.data()[i], " (expected in [0, 1])");
        if (!(gg.data()[i] >= 0 && gg.data()[i] <= 1)) fail("edge_tint[", i, "] = ", gg.data()[i], " (expected in [0, 1])");
        out[size_t(i)] = gulbrandsenIor(rr.data()[i], gg.data()[i]);
    }
    return ownedArray(std::move(out), {rr.shape(0)});
}

/// (n,) CIEDE2000 between linear Rec.709 colours (n, 3), as `compare` measures images
/// (metrics/color_difference.h: reference white = RGB white, D65, Y = 1).
py::array_t<double> deltaE2000(const py::array& test, const py::array& ref) {
    const RealArray a = inputArray<double>(test, "test", 2, 3), b = inputArray<double>(ref, "reference", 2, 3);
    if (a.shape(0) != b.shape(0)) fail("test and reference must have the same number of colours");
    std::vector<double> out(size_t(a.shape(0)));
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        const double* x = a.data() + 3 * i;
        const double* y = b.data() + 3 * i;
        out[size_t(i)] = ciede2000(linearRec709ToLab(x[0], x[1], x[2]), linearRec709ToLab(y[0], y[1], y[2]));
    }
    return ownedArray(std::move(out), {a.shape(0)});
}

}  // namespace

void bindThinFilmIndustry(py::module_& m) {
    m.def("thin_film_khr_rgb", &khrRgb, py::arg("cos_theta"), py::arg("outside_ior"), py::arg("film_ior"), py::arg("thickness_nm"),
          py::arg("base_f0"));
    m.def("thin_film_cycles_4_2_rgb", &cyclesRgb, py::arg("cos_theta"), py::arg("outside_ior"), py::arg("film_ior"),
          py::arg("thickness_nm"), py::arg("base_ior"));
    m.def("gulbrandsen_ior", &gulbrandsen, py::arg("reflectivity"), py::arg("edge_tint"));
    m.def("color_delta_e2000", &deltaE2000, py::arg("test"), py::arg("reference"));
}

}  // namespace iris::python
