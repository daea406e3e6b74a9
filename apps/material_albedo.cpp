// material_albedo: directional albedo ∫ f |cosθi| dωi (materials/albedo.h) of materials at several
// view angles, estimated with each BSDF's own sampling (fixed seed, 200k samples per entry, mean ±
// one standard error), printed as the Markdown tables of docs/materials.md and
// docs/materials_principled_cloth.md, where tests/architecture/doc_tables.py inserts them.
//   material_albedo                 print every table
//   material_albedo --table NAME    one table (--list prints the names)
// Errors print one line and exit 1 (unknown table: 2).
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "core/arena.h"
#include "materials/albedo.h"
#include "materials/material.h"
#include "spectral/wavelengths.h"

using namespace iris;

namespace {

constexpr int kSamples = 200000;
constexpr uint64_t kSeed = 7;

struct Row {
    std::string label;
    std::shared_ptr<Properties> props;
};

std::shared_ptr<Properties> props(const std::string& type, std::initializer_list<std::pair<std::string, PropertyValue>> ps) {
    auto p = std::make_shared<Properties>("bsdf", type, SourceLocation{"material_albedo", 0});
    for (const auto& [n, v] : ps) p->set(n, v, SourceLocation{"material_albedo", 0});
    return p;
}

struct Table {
    std::string name, title;
    std::vector<float> cosines;
    int channel;  // RGB-mode channel reported
    TransportMode mode;
    std::function<std::vector<Row>()> rows;
};

void print(const Table& t) {
    std::printf("**%s**\n\n| configuration |", t.title.c_str());
    for (float c : t.cosines) std::printf(" cosθo = %.2f |", c);
    std::printf("\n|---|");
    for (size_t i = 0; i < t.cosines.size(); ++i) std::printf("---|");
    std::printf("\n");
    for (const Row& row : t.rows()) {
        const MaterialPtr mat = MaterialRegistry::instance().create(*row.props);
        std::printf("| %s |", row.label.c_str());
        for (float c : t.cosines) {
            SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
            Arena arena;
            const BSDF* b = mat->getBSDF(ShadingPoint{}, wl, arena);
            const vec3 wo(std::sqrt(std::max(0.0f, 1 - c * c)), 0.0f, c);
            const AlbedoEstimate a = directionalAlbedo(*b, wo, kSamples, kSeed, t.mode)[t.channel];
            std::printf(" %.4f ± %.4f |", a.mean, a.stderr_);
        }
        std::printf("\n");
    }
}

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

std::vector<Table> tables() {
    const std::vector<float> five = {1.0f, 0.8f, 0.5f, 0.2f, 0.05f};
    std::vector<Table> t;
    t.push_back({"cook_torrance", "cook_torrance, specular term only (kd = 0, f0 = 1): V-cavity G", five, 1,
                 TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     for (float x : {0.05f, 0.3f, 0.8f})
                         r.push_back({fmt("roughness %.2f", x), props("cook_torrance", {{"kd", 0.0f}, {"f0", 1.0f}, {"roughness", x}})});
                     return r;
                 }});
    t.push_back({"phong", "phong, specular lobe only (ρd = 0, ρs = 1)", five, 1, TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     for (float e : {1.0f, 10.0f, 100.0f})
                         r.push_back({fmt("exponent %.0f", e), props("phong", {{"exponent", e}, {"diffuse_reflectance", 0.0f}, {"specular_reflectance", 1.0f}})});
                     return r;
                 }});
    t.push_back({"roughconductor", "roughconductor, perfect mirror Fresnel (material = none): single-scattering energy loss",
                 five, 1, TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     for (const char* dist : {"beckmann", "ggx"})
                         for (float a : {0.1f, 0.3f, 0.8f})
                             for (const char* m : {"separable", "height_correlated"})
                                 r.push_back({std::string(dist) + fmt(" α %.2f ", a) + m,
                                              props("roughconductor", {{"distribution", std::string(dist)}, {"alpha", a}, {"masking", std::string(m)}})});
                     return r;
                 }});
    t.push_back({"roughdielectric", "roughdielectric η = 1.5 from outside, R + T (Importance mode, i.e. without the 1/η² radiance factor)",
                 five, 1, TransportMode::Importance, [] {
                     std::vector<Row> r;
                     for (const char* dist : {"beckmann", "ggx"})
                         for (float a : {0.1f, 0.3f, 0.8f})
                             r.push_back({std::string(dist) + fmt(" α %.2f", a),
                                          props("roughdielectric", {{"distribution", std::string(dist)}, {"alpha", a}, {"int_ior", 1.5f}, {"ext_ior", 1.0f}})});
                     return r;
                 }});
    t.push_back({"principled", "disney (Disney 2012; `principled` in 0.x scenes), base_color 1 unless noted (red channel)", {1.0f, 0.7f, 0.4f, 0.2f, 0.05f}, 0,
                 TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     for (float x : {0.1f, 0.3f, 0.6f, 1.0f})
                         r.push_back({fmt("metallic 1, roughness %.1f", x), props("disney", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", x}})});
                     r.push_back({"metallic 1, roughness 0.6, anisotropic 0.9",
                                  props("disney", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", 0.6f}, {"anisotropic", 0.9f}})});
                     r.push_back({"dielectric, roughness 0.5 (defaults)", props("disney", {{"base_color", 1.0f}})});
                     r.push_back({"dielectric, roughness 1.0", props("disney", {{"base_color", 1.0f}, {"roughness", 1.0f}})});
                     r.push_back({"dielectric, roughness 0.2", props("disney", {{"base_color", 1.0f}, {"roughness", 0.2f}})});
                     for (float x : {1.0f, 0.0f})
                         r.push_back({fmt("specular 0 (Burley diffuse + Schlick F_H residual), roughness %.0f", x),
                                      props("disney", {{"base_color", 1.0f}, {"specular", 0.0f}, {"roughness", x}})});
                     r.push_back({"subsurface 1, roughness 0.5", props("disney", {{"base_color", 1.0f}, {"subsurface", 1.0f}})});
                     r.push_back({"sheen 1, roughness 0.5", props("disney", {{"base_color", 1.0f}, {"sheen", 1.0f}})});
                     r.push_back({"clearcoat 1, gloss 1", props("disney", {{"base_color", 1.0f}, {"clearcoat", 1.0f}, {"clearcoat_gloss", 1.0f}})});
                     r.push_back({"everything 1 (spec 1, sheen 1, clearcoat 1, subsurface 1)",
                                  props("disney", {{"base_color", 1.0f}, {"specular", 1.0f}, {"sheen", 1.0f}, {"clearcoat", 1.0f}, {"subsurface", 1.0f}})});
                     return r;
                 }});
    t.push_back({"principled_mitsuba", "principled (Mitsuba 3), base_color 1 unless noted (red channel)", {1.0f, 0.7f, 0.4f, 0.2f, 0.05f}, 0,
                 TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     r.push_back({"dielectric, roughness 0.5 (defaults)", props("principled", {{"base_color", 1.0f}})});
                     r.push_back({"specular 0 (η = 1: Burley diffuse only), roughness 1", props("principled", {{"base_color", 1.0f}, {"specular", 0.0f}, {"roughness", 1.0f}})});
                     r.push_back({"metallic 1, roughness 0.3", props("principled", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", 0.3f}})});
                     r.push_back({"spec_trans 1, roughness 0.3 (R + T/η², radiance transport)", props("principled", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.3f}})});
                     r.push_back({"clearcoat 1, gloss 1, base 0, specular 0", props("principled", {{"base_color", 0.0f}, {"specular", 0.0f}, {"clearcoat", 1.0f}, {"clearcoat_gloss", 1.0f}})});
                     r.push_back({"sheen 1, roughness 0.5", props("principled", {{"base_color", 1.0f}, {"sheen", 1.0f}})});
                     r.push_back({"principledthin spec_trans 1, roughness 0.3 (R + T)", props("principledthin", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.3f}})});
                     r.push_back({"principledthin diff_trans 1 (R + T)", props("principledthin", {{"base_color", 1.0f}, {"diff_trans", 1.0f}})});
                     return r;
                 }});
    t.push_back({"cloth", "cloth sheen only (base_color 0, sheen_color 1), velvet (reflectance 1), and cloth base 1 + sheen 1",
                 {1.0f, 0.7f, 0.4f, 0.2f, 0.05f}, 0, TransportMode::Radiance, [] {
                     std::vector<Row> r;
                     for (const char* vis : {"charlie", "neubelt"})
                         for (float a : {0.1f, 0.3f, 0.6f, 1.0f})
                             r.push_back({std::string("cloth sheen, ") + vis + fmt(", α = %.1f", a),
                                          props("cloth", {{"base_color", 0.0f}, {"sheen_color", 1.0f}, {"roughness", a}, {"visibility", std::string(vis)}})});
                     for (float s : {0.1f, 0.3f, 0.6f, 1.0f})
                         r.push_back({fmt("velvet, σ = %.1f", s), props("velvet", {{"reflectance", 1.0f}, {"sigma", s}})});
                     r.push_back({"cloth, base 1 + sheen 1, α = 0.3, charlie",
                                  props("cloth", {{"base_color", 1.0f}, {"sheen_color", 1.0f}, {"roughness", 0.3f}})});
                     return r;
                 }});
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const std::vector<Table> all = tables();
        if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
            for (const Table& t : all) std::printf("%s\n", t.name.c_str());
            return 0;
        }
        if (argc == 3 && std::strcmp(argv[1], "--table") == 0) {
            for (const Table& t : all)
                if (t.name == argv[2]) {
                    print(t);
                    return 0;
                }
            std::fprintf(stderr, "material_albedo: unknown table '%s' (--list shows the names)\n", argv[2]);
            return 2;
        }
        if (argc != 1) {
            std::fprintf(stderr, "usage: material_albedo [--table NAME | --list]\n");
            return 2;
        }
        for (const Table& t : all) {
            print(t);
            std::printf("\n");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "material_albedo: %s\n", e.what());
        return 1;
    }
    return 0;
}
