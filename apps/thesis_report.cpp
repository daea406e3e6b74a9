// Measurements for docs/thesis_models.md (printed as Markdown):
//   1. rough plastic table build time (fresh build, TBB, no cache) per distribution;
//   2. Catmull-Rom interpolation error of the tables against brute-force integration;
//   3. directional albedo (white furnace) of the thesis' models for the thesis' parameter sets.
// Usage: thesis_report [--table tables|albedo|all] [--points N] [--samples N]
// (tables: 1 and 2, with timings; albedo: 3, repeatable bit for bit). docs/thesis_models.md gets
// them through tests/architecture/doc_tables.py.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/arena.h"
#include "core/error.h"
#include "core/registry.h"
#include "core/rng.h"
#include "materials/albedo.h"
#include "materials/material.h"
#include "materials/rough_plastic_tables.h"
#include "render/loader/scene_upgrade.h"
#include "spectral/wavelengths.h"

using namespace iris;

namespace {

struct Config {
    std::string name, type;
    std::vector<std::pair<std::string, PropertyValue>> params;
};

std::shared_ptr<Material> makeMaterial(const Config& c) {
    Properties p("bsdf", c.type, SourceLocation{"thesis_report", 0});
    for (const auto& [k, v] : c.params) p.set(k, v, SourceLocation{"thesis_report", 0});
    // The thesis' models as a version 0.x file's objects (Mitsuba 0.6's roughplastic;
    // docs/scene_format.md): the upgrade pass's rules.
    p.setFormatVersion(0);
    upgradeObject(p);
    return MaterialRegistry::instance().create(p);
}

void printTables(int points) {
    const RoughTableResolution res;
    std::printf("### Rough plastic tables (measured by `thesis_report`)\n\n");
    std::printf("Resolution nη × nα × nμ = %d × %d × %d (+ %d × %d for Td), %d-point Gauss-Legendre per "
                "dimension and piece. Errors: %d random points (η ∈ [1,3] uniform, α = u², μ uniform) against "
                "brute force with 32 points.\n\n",
                res.nEta, res.nAlpha, res.nMu, res.nEta, res.nAlpha, res.quadrature, points);
    std::printf("| distribution | build wall / CPU time (s) | max abs err T | max abs err T (μ>0.1 or α>0.1) | RMS err T | max abs err Td |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (auto type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        const RoughTransmittanceTables t = buildRoughTables(type, res);
        const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
        Pcg32 rng(5, 11);
        double maxAll = 0, maxAway = 0, sq = 0, maxTd = 0;
        for (int i = 0; i < points; ++i) {
            const float eta = 1 + 2 * rng.uniform(), a = sqr(rng.uniform()), mu = rng.uniform();
            const double e = std::abs(t.transmittance(eta, a, mu) - roughTransmittanceIntegral(type, eta, a, mu, 32));
            maxAll = std::max(maxAll, e);
            sq += e * e;
            if (mu > 0.1f || a > 0.1f) maxAway = std::max(maxAway, e);
            if (i < points / 10)
                maxTd = std::max(maxTd, std::abs(t.internalDiffuseTransmittance(eta, a) -
                                                 roughInternalDiffuseIntegral(type, eta, a, 32, 48)));
        }
        std::printf("| %s | %.2f / %.2f | %.1e | %.1e | %.1e | %.1e |\n",
                    type == MicrofacetType::Beckmann ? "beckmann" : "ggx", sec, cpu, maxAll, maxAway, std::sqrt(sq / points), maxTd);
    }
}

void printAlbedo(int samples) {
    const PropertyValue tilt14 = VectorValue{vec3(0.24192f, 0, 0.97030f)};
    const PropertyValue tilt10 = VectorValue{vec3(0.1736f, 0, 0.9848f)};
    const PropertyValue eta31 = RGBValue{vec3(1.5f, 1.6f, 1.8f)}, eta42 = RGBValue{vec3(1.8f, 1.7f, 1.6f)};
    const std::vector<Config> configs = {
        {"granier, Table 3.1 (ws = wd = 0.5)", "granier", {{"n0", tilt14}, {"eta_t", eta31}, {"thickness", 76.0f}}},
        {"granier, Table 3.1, ws = wd = 1", "granier",
         {{"n0", tilt14}, {"eta_t", eta31}, {"thickness", 76.0f}, {"ws", 1.0f}, {"wd", 1.0f}}},
        {"granier, Table 3.1 but d = 215 nm, ws = wd = 1", "granier",
         {{"n0", tilt14}, {"eta_t", eta31}, {"thickness", 215.0f}, {"ws", 1.0f}, {"wd", 1.0f}}},
        {"granier, Table 4.2 η, d (e = 130, ws 0.6, wd 0.4)", "granier",
         {{"eta_t", eta42}, {"thickness", 1000.0f}, {"ws", 0.6f}, {"wd", 0.4f}}},
        {"proposed, Table 4.2 (phase total)", "proposed", {}},
        {"proposed, Table 4.2, phase per_reflection", "proposed", {{"phase_mode", std::string("per_reflection")}}},
        {"proposed, Table 4.2, phase off", "proposed", {{"phase", false}}},
        {"proposed, Table 4.2, ws = wd = 1", "proposed", {{"ws", 1.0f}, {"wd", 1.0f}}},
        {"proposed, Tables 4.3/4.4 (α 0.124, ws = wd = 0.5)", "proposed",
         {{"n0", tilt10}, {"eta_t", eta31}, {"thickness", 76.0f}, {"alpha", 0.124f}, {"ws", 0.5f}, {"wd", 0.5f}}},
        {"roughplastic η 1.49, α 0.124, ρ = ks = 1", "roughplastic",
         {{"alpha", 0.124f}, {"diffuse_reflectance", 1.0f}, {"nonlinear", true}}},
    };
    const float cosines[] = {1.0f, 0.8f, 0.6f, 0.4f, 0.2f, 0.1f};
    std::printf("### Directional albedo (RGB mode, %d samples per entry; R/G/B, standard error ≤ %s)\n\n", samples,
                "see last column");
    std::printf("| material | cosθo = 1 | 0.8 | 0.6 | 0.4 | 0.2 | 0.1 | max albedo | max std. error |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const Config& c : configs) {
        const auto m = makeMaterial(c);
        std::printf("| %s |", c.name.c_str());
        double maxA = 0, maxSe = 0;
        for (float co : cosines) {
            Arena arena;
            SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
            const BSDF* bsdf = m->getBSDF(ShadingPoint{}, wl, arena);
            const vec3 wo(std::sqrt(1 - co * co), 0, co);
            const std::vector<AlbedoEstimate> a = directionalAlbedo(*bsdf, wo, samples, 17);
            std::printf(" %.3f / %.3f / %.3f |", a[0].mean, a[1].mean, a[2].mean);
            for (int k = 0; k < 3; ++k) {
                maxA = std::max(maxA, a[k].mean);
                maxSe = std::max(maxSe, a[k].stderr_);
            }
        }
        std::printf(" %.3f | %.1e |\n", maxA, maxSe);
    }
}

}  // namespace

int main(int argc, char** argv) try {
    int points = 5000, samples = 200000;
    std::string table = "all";
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--points")) points = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--samples")) samples = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--table")) table = argv[i + 1];
        else fail("unknown option ", argv[i]);
    }
    if (table != "all" && table != "tables" && table != "albedo") fail("--table must be tables, albedo or all");
    if (table != "albedo") printTables(points);
    if (table == "all") std::printf("\n");
    if (table != "tables") printAlbedo(samples);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "thesis_report: %s\n", e.what());
    return 1;
}
