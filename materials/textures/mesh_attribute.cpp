// The `mesh_attribute` texture (Mitsuba 3, src/textures/mesh_attribute.cpp): `name` (must start with
// "vertex_" or "face_") and `scale` (default 1, multiplies the value). Vertex attributes are
// interpolated with the hit's barycentrics, face attributes are constant per triangle
// (core/mesh.h MeshAttribute::elements).
// As a spectrum texture a 3-channel attribute is linear Rec.709 RGB: returned as it is in RGB mode;
// in spectral mode each element's RGB is upsampled for the texture's kind through the shared
// RGBSpectrumGrid (the path bitmap_texture.cpp takes for large images) and the spectra are blended
// with the barycentric weights, as Mitsuba 3 blends the per-vertex spectra of its srgb model
// (src/render/mesh.h interpolate_attribute). A 1-channel attribute is the grey (v, v, v).
// As a float texture the attribute needs 1 channel (Mitsuba 3's eval_attribute_1 throws for any
// other size); checkMeshAttributes (mesh_attribute_check.cpp) refuses the rest when the scene loads.
#include "core/registry.h"
#include "materials/textures/mesh_attribute.h"
#include "materials/textures/texture.h"
#include "spectral/rgb_spectrum_grid.h"

namespace iris {
namespace {

class AttributeReader {
public:
    AttributeReader(const Properties& p, bool asFloat)
        : name_(p.getString("name")), scale_(p.getFloat("scale", 1.0f)) {
        if (name_.rfind("vertex_", 0) != 0 && name_.rfind("face_", 0) != 0)
            failAt(p.locationOf("name"), "mesh_attribute: name '", name_, "' must start with \"vertex_\" or \"face_\"");
        // How the texture is used, for the per-shape check (mesh_attribute_check.cpp).
        auto use = cachedObject<MeshAttributeUse>(p, [&] { return std::make_shared<MeshAttributeUse>(MeshAttributeUse{name_, false}); });
        use->asFloat = use->asFloat || asFloat;
    }

    /// The attribute at the query if it has `channels` channels (or 3 when `orThree`), else nullptr.
    const MeshAttribute* find(const TextureQuery& q, bool orThree) const {
        const MeshAttribute* a = q.mesh ? q.mesh->findAttribute(name_) : nullptr;
        return a && (a->channels == 1 || (orThree && a->channels == 3)) ? a : nullptr;
    }
    float scale() const { return scale_; }

private:
    std::string name_;
    float scale_;
};

/// An element's value as linear RGB (a 1-channel value as grey).
vec3 elementRGB(const MeshAttribute& a, size_t element) {
    if (a.channels == 1) return vec3(a.value(element, 0));
    return vec3(a.value(element, 0), a.value(element, 1), a.value(element, 2));
}

class MeshAttributeSpectrum final : public SpectrumTexture {
public:
    MeshAttributeSpectrum(const Properties& p, SpectrumKind kind) : reader_(p, false), kind_(kind) {}

    SampledSpectrum eval(const TextureQuery& q, const SampledWavelengths& wl) const override {
        SampledSpectrum s(wl.size());
        const MeshAttribute* a = reader_.find(q, true);
        if (!a) return s;
        size_t element[3];
        float weight[3];
        const int n = a->elements(*q.mesh, q.triangle, q.bary, element, weight);
        if (wl.isRGB()) {
            vec3 rgb(0.0f);
            for (int k = 0; k < n; ++k) rgb += weight[k] * elementRGB(*a, element[k]);
            for (int i = 0; i < 3; ++i) s[i] = reader_.scale() * rgb[i];
            return s;
        }
        const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();
        for (int k = 0; k < n; ++k) s += weight[k] * grid.sample(elementRGB(*a, element[k]), kind_, wl);
        return s * reader_.scale();
    }

private:
    AttributeReader reader_;
    SpectrumKind kind_;
};

class MeshAttributeFloat final : public FloatTexture {
public:
    explicit MeshAttributeFloat(const Properties& p) : reader_(p, true) {}

    float eval(const TextureQuery& q) const override {
        const MeshAttribute* a = reader_.find(q, false);
        return a ? reader_.scale() * a->at(*q.mesh, q.triangle, q.bary, 0) : 0.0f;
    }
    /// The attribute does not vary with uv (Mitsuba 3's mesh_attribute has no eval_1_grad): 0, which
    /// the default's differences in uv would also give, without the two lookups.
    vec2 gradient(const TextureQuery&, float) const override { return vec2(0.0f); }

private:
    AttributeReader reader_;
};

std::shared_ptr<SpectrumTexture> createSpectrum(const Properties& p, SpectrumKind kind) {
    return std::make_shared<MeshAttributeSpectrum>(p, kind);
}
std::shared_ptr<FloatTexture> createFloat(const Properties& p) { return std::make_shared<MeshAttributeFloat>(p); }

}  // namespace

IRIS_REGISTER(SpectrumTextureRegistry, "mesh_attribute", createSpectrum);
IRIS_REGISTER(FloatTextureRegistry, "mesh_attribute", createFloat);

}  // namespace iris
