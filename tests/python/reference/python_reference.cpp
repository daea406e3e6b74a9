// python_reference: the C++ values the Python module's tests compare against, computed by calling
// the library directly (no Python involved). Reads one query per line on stdin and prints one line
// of C hexadecimal floats (%a, exact) per query:
//   film MODE K λ cosθ n0 sub_re sub_im L [re im d]×L  → Rs Rp Ts Tp   (MODE transfer_matrix|airy|truncated|incoherent)
//   bb C cosθ eta1 film_eta d sub_re sub_im             → Belcour–Barla reflectance of channel C
//   ior NAME λ                                          → η κ of a measured conductor
//   bsdf XMLFILE N λ×N wo(3) wi(3)                      → f at the N wavelengths (N = 0: RGB mode)
//   xyz N (λ v)×N                                       → X Y Z of the piecewise-linear spectrum
// A malformed query prints "error: ..." and exits 1.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/arena.h"
#include "core/error.h"
#include "core/xml/xml_parser.h"
#include "materials/material.h"
#include "spectral/belcour_barla.h"
#include "spectral/conductor_presets.h"
#include "spectral/thin_film_stack.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/wavelengths.h"
#include "spectral/xyz.h"

using namespace iris;

namespace {

template <typename T>
T next(std::istringstream& in) {
    T v;
    if (!(in >> v)) fail("malformed query");
    return v;
}

void film(std::istringstream& in) {
    const std::string mode = next<std::string>(in);
    const int K = next<int>(in);
    const double l = next<double>(in), c = next<double>(in), n0 = next<double>(in);
    const double subRe = next<double>(in), subIm = next<double>(in);  // read in order (argument order is unspecified)
    const complexd sub(subRe, subIm);
    std::vector<Layer> layers(size_t(next<int>(in)));
    for (Layer& L : layers) {
        const double re = next<double>(in), im = next<double>(in);
        L = {complexd(re, im), next<double>(in)};
    }
    ThinFilmStackResult r;
    if (mode == "transfer_matrix") r = thinFilmStackRT(l, c, n0, layers, sub);
    else if (mode == "airy") r = singleFilmRT(ThinFilmPhaseMode::Exact, K, l, c, n0, layers.at(0), sub);
    else if (mode == "truncated") r = singleFilmRT(ThinFilmPhaseMode::Truncated, K, l, c, n0, layers.at(0), sub);
    else if (mode == "incoherent") r = singleFilmRT(ThinFilmPhaseMode::Incoherent, K, l, c, n0, layers.at(0), sub);
    else fail("unknown mode ", mode);
    std::printf("%a %a %a %a\n", r.Rs, r.Rp, r.Ts, r.Tp);
}

void belcourBarla(std::istringstream& in) {
    const int ch = next<int>(in);
    const double c = next<double>(in), eta1 = next<double>(in), eta = next<double>(in), d = next<double>(in);
    const double subRe = next<double>(in), subIm = next<double>(in);
    const complexd sub(subRe, subIm);
    std::printf("%a\n", belcourBarlaReflectance(ch, c, eta1, eta, d, sub));
}

void ior(std::istringstream& in) {
    const ConductorSpectra s = loadConductorPreset(next<std::string>(in));
    const float l = float(next<double>(in));
    std::printf("%a %a\n", double(s.eta->eval(l)), double(s.k->eval(l)));
}

void bsdf(std::istringstream& in) {
    std::ifstream file(next<std::string>(in));
    std::stringstream xml;
    xml << file.rdbuf();
    const ParsedScene parsed = parseSceneString("<scene version=\"3.0.0\">" + xml.str() + "\n</scene>", ".");
    const MaterialPtr mat = MaterialRegistry::instance().create(*parsed.objects.at(0));
    std::vector<float> lambdas(size_t(next<int>(in)));
    for (float& l : lambdas) l = next<float>(in);
    vec3 wo, wi;
    for (int k = 0; k < 3; ++k) wo[k] = next<float>(in);
    for (int k = 0; k < 3; ++k) wi[k] = next<float>(in);
    SampledWavelengths wl = lambdas.empty() ? SampledWavelengths::rgb(defaultChannelWavelengths())
                                            : SampledWavelengths::fixed(lambdas.data(), int(lambdas.size()));
    Arena arena;
    const BSDF* b = mat->getBSDF(ShadingPoint{}, wl, arena);
    // Normalised as the module does (x / |x|), so both evaluate the same float directions.
    const SampledSpectrum f = b->eval(wo / glm::length(wo), wi / glm::length(wi), TransportMode::Radiance);
    for (int k = 0; k < wl.size(); ++k) std::printf(k ? " %a" : "%a", double(f[k]));
    std::printf("\n");
}

void xyz(std::istringstream& in) {
    std::vector<float> l(size_t(next<int>(in))), v(l.size());
    for (size_t i = 0; i < l.size(); ++i) {
        l[i] = next<float>(in);
        v[i] = next<float>(in);
    }
    const PiecewiseLinearSpectrum s(l, v, SpectrumKind::Unbounded);
    const dvec3 r = integrateXYZ([&](float lambda) { return s.eval(lambda); });
    std::printf("%a %a %a\n", r.x, r.y, r.z);
}

}  // namespace

int main() {
    std::string line;
    try {
        while (std::getline(std::cin, line)) {
            std::istringstream in(line);
            const std::string what = next<std::string>(in);
            if (what == "film") film(in);
            else if (what == "bb") belcourBarla(in);
            else if (what == "ior") ior(in);
            else if (what == "bsdf") bsdf(in);
            else if (what == "xyz") xyz(in);
            else fail("unknown query '", what, "'");
        }
    } catch (const std::exception& e) {
        std::printf("error: %s\n", e.what());
        return 1;
    }
    return 0;
}
