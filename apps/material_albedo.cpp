// material_albedo: directional albedo ∫ f |cosθi| dωi of the core materials at several incident
// angles, estimated with each BSDF's own sampling (fixed seed, 200k samples, green channel in RGB
// mode), printed as Markdown tables for docs/materials.md.
//   material_albedo            print all tables
// Errors print one line and exit 1.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/arena.h"
#include "core/registry.h"
#include "core/rng.h"
#include "materials/material.h"

using namespace iris;

namespace {

struct Row {
    std::string label;
    std::shared_ptr<Properties> props;
};

std::shared_ptr<Properties> props(const std::string& type, std::initializer_list<std::pair<std::string, PropertyValue>> ps) {
    auto p = std::make_shared<Properties>("bsdf", type, SourceLocation{"material_albedo", 0});
    for (const auto& [n, v] : ps) p->set(n, v, SourceLocation{"material_albedo", 0});
    return p;
}

const float kCosines[] = {1.0f, 0.8f, 0.5f, 0.2f, 0.05f};

void table(const char* title, const std::vector<Row>& rows, TransportMode mode = TransportMode::Radiance) {
    std::printf("\n**%s**\n\n| configuration |", title);
    for (float c : kCosines) std::printf(" cosθo = %.2f |", c);
    std::printf("\n|---|");
    for (size_t i = 0; i < std::size(kCosines); ++i) std::printf("---|");
    std::printf("\n");
    const int n = 200000;
    for (const Row& row : rows) {
        auto mat = MaterialRegistry::instance().create(*row.props);
        std::printf("| %s |", row.label.c_str());
        for (float c : kCosines) {
            SampledWavelengths wl = SampledWavelengths::rgb(vec3(645, 525, 445));
            Arena arena;
            const BSDF* b = mat->getBSDF(ShadingPoint{}, wl, arena);
            const vec3 wo(std::sqrt(std::max(0.0f, 1 - c * c)), 0.0f, c);
            Sampler rng(7, 1234, 0);
            double s = 0, s2 = 0;
            for (int i = 0; i < n; ++i) {
                const float uc = rng.get1D();
                const vec2 u = rng.get2D();
                const auto smp = b->sample(wo, uc, u, mode);
                if (!smp) continue;
                const double w = smp->weight()[1];
                s += w;
                s2 += w * w;
            }
            const double mean = s / n, se = std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
            std::printf(" %.4f ± %.4f |", mean, se);
        }
        std::printf("\n");
    }
}

}  // namespace

int main() {
    try {
        std::vector<Row> ct;
        for (float r : {0.05f, 0.3f, 0.8f})
            ct.push_back({"roughness " + std::to_string(r).substr(0, 4), props("cook_torrance", {{"kd", 0.0f}, {"f0", 1.0f}, {"roughness", r}})});
        table("cook_torrance, specular term only (kd = 0, f0 = 1): V-cavity G", ct);

        std::vector<Row> ph;
        for (float e : {1.0f, 10.0f, 100.0f})
            ph.push_back({"exponent " + std::to_string(int(e)), props("phong", {{"exponent", e}, {"diffuse_reflectance", 0.0f}, {"specular_reflectance", 1.0f}})});
        table("phong, specular lobe only (ρd = 0, ρs = 1)", ph);

        std::vector<Row> rc;
        for (const char* dist : {"beckmann", "ggx"})
            for (float a : {0.1f, 0.3f, 0.8f})
                for (const char* m : {"separable", "height_correlated"})
                    rc.push_back({std::string(dist) + " α " + std::to_string(a).substr(0, 4) + " " + m,
                                  props("roughconductor", {{"distribution", std::string(dist)}, {"alpha", a}, {"masking", std::string(m)}})});
        table("roughconductor, perfect mirror Fresnel (material = none): single-scattering energy loss", rc);

        std::vector<Row> rd;
        for (const char* dist : {"beckmann", "ggx"})
            for (float a : {0.1f, 0.3f, 0.8f})
                rd.push_back({std::string(dist) + " α " + std::to_string(a).substr(0, 4),
                              props("roughdielectric", {{"distribution", std::string(dist)}, {"alpha", a}, {"int_ior", 1.5f}, {"ext_ior", 1.0f}})});
        table("roughdielectric η = 1.5 from outside, R + T (Importance mode, i.e. without the 1/η² radiance factor)", rd,
              TransportMode::Importance);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "material_albedo: %s\n", e.what());
        return 1;
    }
    return 0;
}
