// Thin-film stack optics from Python, over arrays of wavelength and angle: the transfer matrix
// (thinFilmStackRT), the single-film Airy / truncated-K / incoherent sums (spectral/thin_film_stack.h), their
// Mueller matrices (spectral/thin_film_mueller.h) and
// the Belcour–Barla RGB reflectance (spectral/belcour_barla.h). The package broadcasts the inputs
// to flat arrays of one length n; every value is the C++ function's own double result.
#include <algorithm>
#include <cmath>

#include "apps/python/bindings.h"
#include "spectral/belcour_barla.h"
#include "spectral/conductor_presets.h"
#include "spectral/thin_film_mueller.h"
#include "spectral/thin_film_stack.h"
#include "spectral/ior_presets.h"

namespace iris::python {

namespace {

using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using ComplexArray = py::array_t<complexd, py::array::c_style | py::array::forcecast>;

void checkFinite(double v, const char* name, py::ssize_t i) {
    if (!std::isfinite(v)) fail(name, "[", i, "] is ", v, " (expected a finite number)");
}

void checkIndex(complexd v, const char* name, py::ssize_t i) {
    if (!std::isfinite(v.real()) || !std::isfinite(v.imag()) || v.real() <= 0 || v.imag() < 0)
        fail(name, "[", i, "] = ", v.real(), "+", v.imag(), "i is not a valid index of refraction (need n > 0, k >= 0, finite)");
}

/// The inputs common to every stack function, validated (iris::Error names the bad entry).
struct StackInputs {
    RealArray lambda, cosTheta, incident;
    py::ssize_t n = 0;
};

StackInputs stackInputs(const py::array& lambdaNm, const py::array& cosTheta, const py::array& incidentIor) {
    StackInputs in{inputArray<double>(lambdaNm, "wavelengths_nm", 1), inputArray<double>(cosTheta, "cos_theta", 1),
                   inputArray<double>(incidentIor, "incident_ior", 1)};
    in.n = in.lambda.shape(0);
    if (in.cosTheta.shape(0) != in.n || in.incident.shape(0) != in.n) fail("wavelengths_nm, cos_theta and incident_ior must have the same length");
    for (py::ssize_t i = 0; i < in.n; ++i) {
        checkFinite(in.lambda.data()[i], "wavelengths_nm", i);
        checkFinite(in.cosTheta.data()[i], "cos_theta", i);
        checkFinite(in.incident.data()[i], "incident_ior", i);
        if (!(in.lambda.data()[i] > 0)) fail("wavelengths_nm[", i, "] = ", in.lambda.data()[i], " (expected > 0 nm)");
        if (!(in.cosTheta.data()[i] >= 0 && in.cosTheta.data()[i] <= 1)) fail("cos_theta[", i, "] = ", in.cosTheta.data()[i], " (expected in [0, 1])");
        if (!(in.incident.data()[i] > 0)) fail("incident_ior[", i, "] = ", in.incident.data()[i], " (expected > 0)");
    }
    return in;
}

ThinFilmPhaseMode phaseMode(const std::string& mode) {
    if (mode == "airy") return ThinFilmPhaseMode::Exact;
    if (mode == "truncated") return ThinFilmPhaseMode::Truncated;
    if (mode == "incoherent") return ThinFilmPhaseMode::Incoherent;
    fail("mode: unknown '", mode, "' (expected transfer_matrix, airy, truncated or incoherent)");
}

/// The validated arguments of the stack functions: flat inputs of length n, L layers.
struct StackArgs {
    StackInputs in;
    ComplexArray iors, sub;
    RealArray d;
    py::ssize_t L = 0;
    bool transfer = true;
    ThinFilmPhaseMode single = ThinFilmPhaseMode::Exact;
    int K = 0;
};

StackArgs stackArgs(const py::array& lambdaNm, const py::array& cosTheta, const py::array& incidentIor, const py::array& layerIors,
                    const py::array& thicknesses, const py::array& substrateIor, const std::string& mode, int K) {
    StackArgs a{stackInputs(lambdaNm, cosTheta, incidentIor), inputArray<complexd>(layerIors, "layer iors", 2),
                inputArray<complexd>(substrateIor, "substrate_ior", 1), inputArray<double>(thicknesses, "thicknesses", 1)};
    a.L = a.d.shape(0);
    const py::ssize_t L = a.L, n = a.in.n;
    if (a.iors.shape(0) != L || a.iors.shape(1) != n) fail("layer iors: expected shape (", L, ", ", n, ")");
    if (a.sub.shape(0) != n) fail("substrate_ior: expected ", n, " values");
    for (py::ssize_t j = 0; j < L; ++j) {
        checkFinite(a.d.data()[j], "thickness of layer", j);
        if (a.d.data()[j] < 0) fail("layer ", j, ": thickness ", a.d.data()[j], " nm is negative");
        for (py::ssize_t i = 0; i < n; ++i) checkIndex(a.iors.data()[j * n + i], strCat("layer ", j, " ior").c_str(), i);
    }
    for (py::ssize_t i = 0; i < n; ++i) checkIndex(a.sub.data()[i], "substrate_ior", i);
    a.transfer = mode == "transfer_matrix";
    a.single = a.transfer ? ThinFilmPhaseMode::Exact : phaseMode(mode);
    if (!a.transfer && L != 1) fail("mode '", mode, "' is a single-film formula: give exactly one layer (got ", L, ")");
    if (a.single == ThinFilmPhaseMode::Truncated && K < 0) fail("K: must be >= 0 round trips, got ", K);
    a.K = K;
    return a;
}

/// f(i, layers) for every point i with its stack (layers as Layer values), the GIL released.
template <typename F>
void forEachStack(const StackArgs& a, F&& f) {
    py::gil_scoped_release release;
    std::vector<Layer> layers(static_cast<size_t>(a.L));
    for (py::ssize_t i = 0; i < a.in.n; ++i) {
        for (py::ssize_t j = 0; j < a.L; ++j) layers[size_t(j)] = {a.iors.data()[j * a.in.n + i], a.d.data()[j]};
        f(i, layers);
    }
}

/// (4, n) array of Rs, Rp, Ts, Tp.
py::array_t<double> stackRT(const py::array& lambdaNm, const py::array& cosTheta, const py::array& incidentIor,
                            const py::array& layerIors, const py::array& thicknesses, const py::array& substrateIor,
                            const std::string& mode, int K) {
    const StackArgs a = stackArgs(lambdaNm, cosTheta, incidentIor, layerIors, thicknesses, substrateIor, mode, K);
    const py::ssize_t n = a.in.n;
    std::vector<double> out(size_t(4 * n));
    forEachStack(a, [&](py::ssize_t i, const std::vector<Layer>& layers) {
        const double l = a.in.lambda.data()[i], c = a.in.cosTheta.data()[i], n0 = a.in.incident.data()[i];
        const ThinFilmStackResult r = a.transfer ? thinFilmStackRT(l, c, n0, layers, a.sub.data()[i])
                                                 : singleFilmRT(a.single, a.K, l, c, n0, layers[0], a.sub.data()[i]);
        out[size_t(i)] = r.Rs;
        out[size_t(n + i)] = r.Rp;
        out[size_t(2 * n + i)] = r.Ts;
        out[size_t(3 * n + i)] = r.Tp;
    });
    return ownedArray(std::move(out), {4, n});
}

/// (2, n, 4, 4) array: the reflection and transmission Mueller matrices (spectral/thin_film_mueller.h,
/// s-axis bases), from stackPolarization (transfer matrix) or singleFilmPolarization (one film).
py::array_t<double> stackMueller(const py::array& lambdaNm, const py::array& cosTheta, const py::array& incidentIor,
                                 const py::array& layerIors, const py::array& thicknesses, const py::array& substrateIor,
                                 const std::string& mode, int K) {
    const StackArgs a = stackArgs(lambdaNm, cosTheta, incidentIor, layerIors, thicknesses, substrateIor, mode, K);
    const py::ssize_t n = a.in.n;
    std::vector<double> out(size_t(2 * n * 16));
    forEachStack(a, [&](py::ssize_t i, const std::vector<Layer>& layers) {
        const double l = a.in.lambda.data()[i], c = a.in.cosTheta.data()[i], n0 = a.in.incident.data()[i];
        const FilmPolarization p = a.transfer ? stackPolarization(l, c, n0, layers, a.sub.data()[i])
                                              : singleFilmPolarization(a.single, a.K, l, c, n0, layers[0], a.sub.data()[i]);
        const Mueller4d m[2] = {reflectionMueller(p), transmissionMueller(p)};
        for (int t = 0; t < 2; ++t)
            for (int r = 0; r < 4; ++r)
                for (int col = 0; col < 4; ++col) out[size_t(((t * n + i) * 4 + r) * 4 + col)] = m[t].m[r][col];
    });
    return ownedArray(std::move(out), {py::ssize_t(2), n, py::ssize_t(4), py::ssize_t(4)});
}

/// (n, 3) Belcour–Barla RGB reflectance; substrate indices per channel (n, 3).
py::array_t<double> belcourBarla(const py::array& cosTheta, const py::array& incidentIor, const py::array& filmIor,
                                 const py::array& thickness, const py::array& substrateIor) {
    const RealArray c = inputArray<double>(cosTheta, "cos_theta", 1), n0 = inputArray<double>(incidentIor, "incident_ior", 1);
    const RealArray eta = inputArray<double>(filmIor, "film_ior", 1), d = inputArray<double>(thickness, "thickness_nm", 1);
    const ComplexArray sub = inputArray<complexd>(substrateIor, "substrate_ior", 2, 3);
    const py::ssize_t n = c.shape(0);
    if (n0.shape(0) != n || eta.shape(0) != n || d.shape(0) != n || sub.shape(0) != n)
        fail("cos_theta, incident_ior, film_ior, thickness_nm and substrate_ior must have the same length");
    for (py::ssize_t i = 0; i < n; ++i) {
        checkFinite(c.data()[i], "cos_theta", i);
        checkFinite(d.data()[i], "thickness_nm", i);
        if (!(c.data()[i] >= 0 && c.data()[i] <= 1)) fail("cos_theta[", i, "] = ", c.data()[i], " (expected in [0, 1])");
        if (d.data()[i] < 0) fail("thickness_nm[", i, "] = ", d.data()[i], " nm is negative");
        checkIndex(n0.data()[i], "incident_ior", i);
        checkIndex(eta.data()[i], "film_ior", i);
        for (int k = 0; k < 3; ++k) checkIndex(sub.data()[3 * i + k], "substrate_ior", i);
    }
    std::vector<double> out(size_t(3 * n));
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k)
                out[size_t(3 * i + k)] = belcourBarlaReflectance(k, c.data()[i], n0.data()[i], eta.data()[i], d.data()[i], sub.data()[3 * i + k]);
    }
    return ownedArray(std::move(out), {n, 3});
}

/// η + iκ of a named material at the given wavelengths: a measured conductor (spectral/data/ior,
/// conductorPresetNames) or a dielectric preset (a constant, iorPresetNames).
py::array_t<complexd> namedIor(const std::string& name, const py::array& lambdaNm) {
    const RealArray l = inputArray<double>(lambdaNm, "wavelengths_nm", 1);
    const py::ssize_t n = l.shape(0);
    std::vector<complexd> out(static_cast<size_t>(n));
    float eta = 0;
    if (lookupIORPreset(name, &eta)) {
        std::fill(out.begin(), out.end(), complexd(eta, 0.0));
    } else {
        const auto& conductors = conductorPresetNames();
        if (name == "none" || std::find(conductors.begin(), conductors.end(), name) == conductors.end()) {
            std::string list;
            for (const auto& c : conductors)
                if (c != "none") list += (list.empty() ? "" : ", ") + c;
            fail("unknown index of refraction '", name, "' (dielectrics: ", iorPresetList(), "; measured conductors: ", list, ")");
        }
        const ConductorSpectra s = loadConductorPreset(name);
        for (py::ssize_t i = 0; i < n; ++i) {
            const float li = float(l.data()[i]);
            out[size_t(i)] = complexd(s.eta->eval(li), s.k->eval(li));
        }
    }
    return ownedArray(std::move(out), {n});
}

}  // namespace

void bindFilm(py::module_& m) {
    m.def("film_stack_rt", &stackRT, py::arg("wavelengths_nm"), py::arg("cos_theta"), py::arg("incident_ior"),
          py::arg("layer_iors"), py::arg("thicknesses"), py::arg("substrate_ior"), py::arg("mode"), py::arg("K"));
    m.def("film_stack_mueller", &stackMueller, py::arg("wavelengths_nm"), py::arg("cos_theta"), py::arg("incident_ior"),
          py::arg("layer_iors"), py::arg("thicknesses"), py::arg("substrate_ior"), py::arg("mode"), py::arg("K"));
    m.def("film_belcour_barla", &belcourBarla, py::arg("cos_theta"), py::arg("incident_ior"), py::arg("film_ior"),
          py::arg("thickness_nm"), py::arg("substrate_ior"));
    m.def("named_ior", &namedIor, py::arg("name"), py::arg("wavelengths_nm"));
    m.def("ior_preset_names", &iorPresetNames);
    m.def("conductor_names", [] {
        std::vector<std::string> names;
        for (const auto& n : conductorPresetNames())
            if (n != "none") names.push_back(n);
        return names;
    });
}

}  // namespace iris::python
