// Normal-map wrapper (Mitsuba 3 plugin "normalmap", v3.7 src/bsdfs/normalmap.cpp): perturbs the
// shading normal with a tangent-space normal map; the nested material is evaluated in the
// perturbed frame by PerturbedBSDF (materials/perturbed_frame.h).
//
// Parameters: `normalmap` — a texture (normally <texture type="bitmap"> with raw="true", since
// 8-bit images are otherwise sRGB-decoded, as in Mitsuba; or a `rawconstant`) or an <rgb>
// constant; RGB in [0, 1] maps to the tangent-space normal 2·rgb − 1 (x along the shading
// tangent s, the ∂p/∂u direction; y along t = n × s; z along the shading normal; Mitsuba 3's
// convention, NormalMap::perturbation). `flip_invalid_normals`, `use_shadowing_function` (both
// default true, as Mitsuba 3). One nested <bsdf>.
// The map is always read as RGB (the texture is evaluated with RGB-mode wavelengths, where
// textures return their RGB values unchanged), so the frame never depends on the wavelengths.
#include "materials/perturbed_frame.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class NormalMapMaterial final : public PerturbedMaterial {
public:
    NormalMapMaterial(SpectrumTexturePtr map, std::shared_ptr<Material> nested, const PerturbOptions& opt)
        : PerturbedMaterial(std::move(nested), opt), map_(std::move(map)) {}

    vec3 perturbation(const ShadingPoint& sp) const override {
        static const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
        const SampledSpectrum c = map_->eval(sp.tex, rgbWl);
        return vec3(2.0f * c[0] - 1.0f, 2.0f * c[1] - 1.0f, 2.0f * c[2] - 1.0f);
    }

private:
    SpectrumTexturePtr map_;
};

std::shared_ptr<Material> createNormalMap(const Properties& p) {
    auto map = getSpectrumTexture(p, "normalmap", SpectrumKind::Unbounded);
    const PerturbOptions opt = PerturbOptions::read(p);
    auto nested = createNestedMaterial(p, "normalmap", {"normalmap", "flip_invalid_normals", "use_shadowing_function"});
    return std::make_shared<NormalMapMaterial>(std::move(map), std::move(nested), opt);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "normalmap", createNormalMap);

}  // namespace iris
