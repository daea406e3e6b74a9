// Bump-map wrapper (Mitsuba 3 plugin "bumpmap", v3.7 src/bsdfs/bumpmap.cpp): perturbs the shading
// normal with the gradient of a height texture (Blinn 1978, "Simulation of Wrinkled Surfaces");
// the nested material is evaluated in the perturbed frame by PerturbedBSDF
// (materials/perturbed_frame.h).
//
// Parameters: one float texture under any name (Mitsuba style; normally a bitmap with
// raw="true"), `scale` (gradient multiplier, default 1), `flip_invalid_normals` and
// `use_shadowing_function` (default true, as Mitsuba 3), `gradient_step` (iris extension: the uv
// step δ of the central differences for textures without an analytic gradient, default 1e-3;
// bitmaps and constants differentiate exactly, as Mitsuba's eval_1_grad), one nested <bsdf>.
#include "materials/perturbed_frame.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class BumpMapMaterial final : public PerturbedMaterial {
public:
    BumpMapMaterial(FloatTexturePtr height, float scale, float step, std::shared_ptr<Material> nested,
                    const PerturbOptions& opt)
        : PerturbedMaterial(std::move(nested), opt), height_(std::move(height)), scale_(scale), step_(step) {}

    /// Mitsuba 3 BumpMap::perturbation: the surface displaced by h along the shading normal n,
    /// with the term in ∂n/∂u dropped (Blinn 1978; pbrt-v4 §10.5.3): with g = scale·∇h and the
    /// parametrisation's ∂p/∂u, ∂p/∂v first projected onto the shading tangent plane,
    ///   ∂p'/∂u = ∂p/∂u + (g_u − n·∂p/∂u) n,  ∂p'/∂v = ∂p/∂v + (g_v − n·∂p/∂v) n,
    ///   n' ∝ ∂p'/∂u × ∂p'/∂v, turned to the side of the geometric normal.
    vec3 perturbation(const ShadingPoint& sp) const override {
        const vec2 g = scale_ * height_->gradient(sp.tex, step_);
        const vec3& n = sp.shading.n;
        const vec3 dpdu = sp.dpdu + (g.x - glm::dot(n, sp.dpdu)) * n;
        const vec3 dpdv = sp.dpdv + (g.y - glm::dot(n, sp.dpdv)) * n;
        vec3 c = glm::cross(dpdu, dpdv);
        if (glm::dot(sp.ng, c) < 0) c = -c;
        return sp.shading.toLocal(c);
    }

private:
    FloatTexturePtr height_;
    float scale_, step_;
};

std::shared_ptr<Material> createBumpMap(const Properties& p) {
    const float scale = p.getFloat("scale", 1.0f);
    const float step = p.getFloat("gradient_step", 1e-3f);
    if (!(step > 0)) failAt(p.locationOf("gradient_step"), "bumpmap: gradient_step must be > 0, got ", step);
    const PerturbOptions opt = PerturbOptions::read(p);
    // The height texture: an unnamed <texture> child or a <texture> under any name.
    std::vector<FloatTexturePtr> textures;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == "texture") textures.push_back(FloatTextureRegistry::instance().create(*c));
    std::set<std::string> own{"scale", "gradient_step", "flip_invalid_normals", "use_shadowing_function"};
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
    return std::make_shared<BumpMapMaterial>(std::move(textures[0]), scale, step, std::move(nested), opt);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "bumpmap", createBumpMap);

}  // namespace iris
