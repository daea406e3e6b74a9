// Normal-map wrapper (Mitsuba 3 plugin "normalmap"): perturbs the shading frame with a
// tangent-space normal map and forwards everything else to the nested material.
//
// Parameters: `normalmap` — a texture (normally <texture type="bitmap"> with raw="true", since
// 8-bit images are otherwise sRGB-decoded, as in Mitsuba) or an <rgb> constant; RGB in [0, 1]
// maps to the tangent-space normal 2·rgb − 1 (x along the tangent s = ∂p/∂u, y along t = n × s,
// z along the shading normal; Mitsuba 3's convention). One nested <bsdf>.
// The map is always read as RGB (the texture is evaluated with RGB-mode wavelengths, where
// textures return their RGB values unchanged), so the frame never depends on the wavelengths.
#include "materials/perturbed_frame.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class NormalMapMaterial final : public Material {
public:
    NormalMapMaterial(SpectrumTexturePtr map, std::shared_ptr<Material> nested)
        : map_(std::move(map)), nested_(std::move(nested)) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return nested_->getBSDF(sp, wl, arena);
    }

    Frame shadingFrame(const ShadingPoint& sp) const override {
        static const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
        const SampledSpectrum c = map_->eval(sp.tex, rgbWl);
        const vec3 nTs(2.0f * c[0] - 1.0f, 2.0f * c[1] - 1.0f, 2.0f * c[2] - 1.0f);
        ShadingPoint perturbed = sp;
        perturbed.shading = frameFromTangentSpaceNormal(sp.shading, nTs);
        return nested_->shadingFrame(perturbed);  // a nested perturbation applies on top of this one
    }

private:
    SpectrumTexturePtr map_;
    std::shared_ptr<Material> nested_;
};

std::shared_ptr<Material> createNormalMap(const Properties& p) {
    auto map = getSpectrumTexture(p, "normalmap", SpectrumKind::Unbounded);
    auto nested = createNestedMaterial(p, "normalmap", {"normalmap"});
    return std::make_shared<NormalMapMaterial>(std::move(map), std::move(nested));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "normalmap", createNormalMap);

}  // namespace iris
