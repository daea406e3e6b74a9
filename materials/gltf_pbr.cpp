#include "materials/gltf_pbr.h"

#include <algorithm>

#include "core/registry.h"
#include "materials/gltf_pbr_bsdf.h"
#include "spectral/rgb_spectrum_grid.h"

namespace iris::gltf {

ThinFilmRGBMode parseThinFilmRGBMode(const std::string& name) {
    if (name == "point") return ThinFilmRGBMode::Exact;
    if (name == "khr_iridescence") return ThinFilmRGBMode::Khr;
    if (name == "cycles_4_2") return ThinFilmRGBMode::Cycles42;
    fail("rgb_mode '", name, "' is not supported by gltf_pbr (supported: point, khr_iridescence, cycles_4_2)");
}

namespace {

/// RGB per lane: the channels themselves in RGB mode, else the reflectance spectrum that
/// upsamples it (spectral/rgb_spectrum_grid.h) at the path's wavelengths.
SampledSpectrum lanes(const vec3& rgb, const SampledWavelengths& wl) {
    if (wl.isRGB()) {
        SampledSpectrum s(3);
        for (int c = 0; c < 3; ++c) s[c] = rgb[c];
        return s;
    }
    return RGBSpectrumGrid::instance().sample(glm::clamp(rgb, vec3(0.0f), vec3(1.0f)), SpectrumKind::Reflectance, wl);
}

float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }

class PbrMaterial final : public Material {
public:
    explicit PbrMaterial(PbrParams p) : p_(std::move(p)) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<PbrBSDF>(point(sp.tex, wl));
    }

private:
    /// §3.9.2 and the extensions' "factor × texture" rules at one point.
    PbrPoint point(const TextureQuery& q, const SampledWavelengths& wl) const {
        PbrPoint r;
        const vec4 vc = p_.vertexColor ? vertexColorAt(q) : vec4(1.0f);
        r.baseRGB = glm::clamp(p_.baseColor.at(q) * vec3(vc), vec3(0.0f), vec3(1.0f));
        r.specularColorRGB = glm::max(p_.specularColor.at(q), vec3(0.0f));
        const vec3 sheen = glm::clamp(p_.sheenColor.at(q), vec3(0.0f), vec3(1.0f));
        r.base = lanes(r.baseRGB, wl);
        r.specularColor = lanes(r.specularColorRGB, wl);
        r.sheenColor = lanes(sheen, wl);
        r.sheenMax = std::max(sheen.x, std::max(sheen.y, sheen.z));
        r.lambda = SampledSpectrum(wl.size());
        for (int i = 0; i < wl.size(); ++i) r.lambda[i] = wl.lambda(i);
        r.rgb = wl.isRGB();
        r.metallic = clamp01(p_.metallic.at(q));
        const float rough = clamp01(p_.roughness.at(q));
        r.alpha = rough * rough;  // Appendix B: α = roughness²
        r.ior = p_.ior;
        r.specular = clamp01(p_.specular.at(q));
        r.transmission = clamp01(p_.transmission.at(q));
        r.clearcoat = clamp01(p_.clearcoat.at(q));
        const float coatRough = clamp01(p_.clearcoatRoughness.at(q));
        r.coatAlpha = coatRough * coatRough;
        r.sheenRoughness = clamp01(p_.sheenRoughness.at(q));
        r.sheenAlpha = r.sheenRoughness * r.sheenRoughness;
        r.iridescence = clamp01(p_.iridescence.at(q));
        // KHR_materials_iridescence: thickness = mix(min, max, texture.g); without texture, max.
        const float t = p_.thicknessTexture ? p_.thicknessTexture->rgba(q).g : 1.0f;
        r.thicknessNm = std::max(0.0f, p_.thicknessMin + (p_.thicknessMax - p_.thicknessMin) * t);
        r.filmIor = p_.iridescenceIor;
        r.edgeTint = p_.edgeTint;
        r.mode = p_.rgbMode;
        r.doubleSided = p_.doubleSided;
        r.volume = p_.volume;
        r.opacity = opacity(q, vc.a);
        return r;
    }

    /// §3.9.4 alpha coverage: mask → 0 or 1 by the cutoff, blend → alpha (as coverage), opaque → 1.
    float opacity(const TextureQuery& q, float vertexAlpha) const {
        if (p_.alphaMode == AlphaMode::Opaque) return 1.0f;
        const float a = clamp01(p_.baseAlpha.at(q) * vertexAlpha);
        if (p_.alphaMode == AlphaMode::Mask) return a >= p_.alphaCutoff ? 1.0f : 0.0f;
        return a;
    }

    PbrParams p_;
};

/// Scene-file parameters of `gltf_pbr` (constants; names as the glTF JSON's, snake_case).
std::shared_ptr<Material> createPbr(const Properties& pr) {
    PbrParams p;
    auto unit = [&](const char* name, float def) {
        const float v = pr.getFloat(name, def);
        if (!(v >= 0 && v <= 1)) failAt(pr.locationOf(name), "gltf_pbr: ", name, " must be in [0, 1], got ", v);
        return v;
    };
    p.baseColor.factor = pr.getRGB("base_color", vec3(1.0f));
    p.metallic.factor = unit("metallic", 1.0f);
    p.roughness.factor = unit("roughness", 1.0f);
    p.ior = pr.getFloat("ior", 1.5f);
    if (!(p.ior >= 1.0f)) failAt(pr.locationOf("ior"), "gltf_pbr: ior must be >= 1, got ", p.ior);
    p.specular.factor = unit("specular", 1.0f);
    p.specularColor.factor = pr.getRGB("specular_color", vec3(1.0f));
    p.transmission.factor = unit("transmission", 0.0f);
    p.clearcoat.factor = unit("clearcoat", 0.0f);
    p.clearcoatRoughness.factor = unit("clearcoat_roughness", 0.0f);
    p.sheenColor.factor = pr.getRGB("sheen_color", vec3(0.0f));
    p.sheenRoughness.factor = unit("sheen_roughness", 0.0f);
    p.iridescence.factor = unit("iridescence", 0.0f);
    p.iridescenceIor = pr.getFloat("iridescence_ior", 1.3f);
    if (!(p.iridescenceIor >= 1.0f)) failAt(pr.locationOf("iridescence_ior"), "gltf_pbr: iridescence_ior must be >= 1");
    p.thicknessMax = p.thicknessMin = pr.getFloat("iridescence_thickness", 400.0f);
    if (!(p.thicknessMax >= 0)) failAt(pr.locationOf("iridescence_thickness"), "gltf_pbr: iridescence_thickness must be >= 0 nm");
    p.edgeTint = pr.has("edge_tint") ? unit("edge_tint", 1.0f) : -1.0f;
    p.doubleSided = pr.getBool("double_sided", true);
    const float thickness = pr.getFloat("thickness", 0.0f);  // KHR_materials_volume thicknessFactor: > 0 is a volume boundary
    if (!(thickness >= 0)) failAt(pr.locationOf("thickness"), "gltf_pbr: thickness must be >= 0, got ", thickness);
    p.volume = thickness > 0 && p.transmission.factor > 0;  // as the loader: a volume needs transmission
    p.rgbMode = withLocation(pr.locationOf("rgb_mode"), [&] { return parseThinFilmRGBMode(pr.getString("rgb_mode", "point")); });
    return std::make_shared<PbrMaterial>(std::move(p));
}

}  // namespace

MaterialPtr makePbrMaterial(PbrParams params) { return std::make_shared<PbrMaterial>(std::move(params)); }

IRIS_REGISTER(MaterialRegistry, "gltf_pbr", createPbr);

}  // namespace iris::gltf
