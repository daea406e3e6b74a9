// Bump-map wrapper (Mitsuba 3 plugin "bumpmap"): perturbs the shading frame with the gradient of
// a height texture (Blinn 1978; see frameFromHeightGradient in perturbed_frame.h for the maths and
// its assumption about ∂p/∂v) and forwards everything else to the nested material.
//
// Parameters: one float texture under any name (Mitsuba style; normally a bitmap with
// raw="true"), `scale` (height multiplier, default 1), `gradient_step` (iris extension: the uv
// step δ of the central differences ∂h/∂u ≈ (h(u+δ) − h(u−δ))/(2δ), default 1e-3 — about one
// texel of a 1k map; Mitsuba differentiates the bilinear interpolant instead), one nested <bsdf>.
#include "materials/perturbed_frame.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class BumpMapMaterial final : public Material {
public:
    BumpMapMaterial(FloatTexturePtr height, float scale, float step, std::shared_ptr<Material> nested)
        : height_(std::move(height)), scale_(scale), step_(step), nested_(std::move(nested)) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return nested_->getBSDF(sp, wl, arena);
    }

    Frame shadingFrame(const ShadingPoint& sp) const override {
        ShadingPoint perturbed = sp;
        perturbed.shading = frameFromHeightGradient(sp.shading, sp.dpdu, scale_ * heightGradient(sp.tex));
        return nested_->shadingFrame(perturbed);
    }

    /// (∂h/∂u, ∂h/∂v) by central differences.
    vec2 heightGradient(const TextureQuery& q) const {
        auto at = [&](float du, float dv) {
            TextureQuery s = q;
            s.uv += vec2(du, dv);
            return height_->eval(s);
        };
        const float inv = 0.5f / step_;
        return vec2((at(step_, 0) - at(-step_, 0)) * inv, (at(0, step_) - at(0, -step_)) * inv);
    }

private:
    FloatTexturePtr height_;
    float scale_, step_;
    std::shared_ptr<Material> nested_;
};

std::shared_ptr<Material> createBumpMap(const Properties& p) {
    const float scale = p.getFloat("scale", 1.0f);
    const float step = p.getFloat("gradient_step", 1e-3f);
    if (!(step > 0)) failAt(p.locationOf("gradient_step"), "bumpmap: gradient_step must be > 0, got ", step);
    // The height texture: an unnamed <texture> child or a <texture> under any name.
    std::vector<FloatTexturePtr> textures;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == "texture") textures.push_back(FloatTextureRegistry::instance().create(*c));
    std::set<std::string> own{"scale", "gradient_step"};
    for (const std::string& name : p.names()) {
        if (own.count(name)) continue;
        const PropertiesPtr obj = nestedObjectOrFail(p, name, "bumpmap", own);
        if (obj->tag() == "texture") {
            textures.push_back(getFloatTexture(p, name));
            own.insert(name);
        }
    }
    if (textures.size() != 1)
        failAt(p.location(), "bumpmap: expected exactly one nested height texture, got ", textures.size());
    auto nested = createNestedMaterial(p, "bumpmap", own);
    return std::make_shared<BumpMapMaterial>(std::move(textures[0]), scale, step, std::move(nested));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "bumpmap", createBumpMap);

}  // namespace iris
