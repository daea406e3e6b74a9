#include "render/loader/gltf_material.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "materials/gltf_normal_map.h"
#include "render/loader/gltf_images.h"
#include "render/loader/gltf_volume.h"
#include "spectral/rgb_spectrum_grid.h"
#include "spectral/spectrum_factory.h"

namespace iris::gltf {

namespace {

double number(const tinygltf::Value& v, const char* key, double def) {
    if (!v.IsObject() || !v.Has(key)) return def;
    const tinygltf::Value& x = v.Get(key);
    return x.IsNumber() ? x.GetNumberAsDouble() : def;
}

/// An index or set number of a JSON object as an int: absent or NaN → def, otherwise clamped to
/// [−1, INT_MAX] (a converted double out of int's range would be undefined behaviour), so that an
/// absurd index still fails the range checks that name it.
int integer(const tinygltf::Value& v, const char* key, int def) {
    const double x = number(v, key, def);
    if (std::isnan(x)) return def;
    return int(std::clamp(x, -1.0, double(std::numeric_limits<int>::max())));
}

vec3 color(const tinygltf::Value& v, const char* key, const vec3& def) {
    if (!v.IsObject() || !v.Has(key)) return def;
    const tinygltf::Value& a = v.Get(key);
    if (!a.IsArray() || a.ArrayLen() < 3) return def;
    vec3 c;
    for (int i = 0; i < 3; ++i) c[i] = float(a.Get(i).IsNumber() ? a.Get(i).GetNumberAsDouble() : def[i]);
    return c;
}

const tinygltf::Value* extension(const tinygltf::Material& m, const char* name) {
    const auto it = m.extensions.find(name);
    return it == m.extensions.end() ? nullptr : &it->second;
}

/// Emission (§3.9.3) as a texture: factor × the sRGB-decoded texture, an illuminant spectrum.
class EmissionTexture final : public SpectrumTexture {
public:
    EmissionTexture(vec3 factor, TexturePtr tex) : factor_(factor), tex_(std::move(tex)) {}
    SampledSpectrum eval(const TextureQuery& q, const SampledWavelengths& wl) const override {
        return RGBSpectrumGrid::instance().sample(glm::max(factor_ * vec3(tex_->rgba(q)), vec3(0.0f)), SpectrumKind::Illuminant, wl);
    }

private:
    vec3 factor_;
    TexturePtr tex_;
};

}  // namespace

const ShapeMaterial& MaterialCache::material(int index) {
    auto it = materials_.find(index);
    if (it == materials_.end()) it = materials_.emplace(index, build(index)).first;
    return it->second;
}

std::shared_ptr<const Bitmap> MaterialCache::image(int index, bool srgb, const std::string& path) {
    auto key = std::make_pair(index, srgb);
    auto it = images_.find(key);
    if (it == images_.end()) it = images_.emplace(key, decodeImage(doc_, index, srgb, path)).first;
    return it->second;
}

const tinygltf::Texture& MaterialCache::checkTexture(int index, int texCoord, const std::string& path) {
    if (size_t(index) >= doc_.model.textures.size()) failAtPath(doc_, path + "/index", "texture ", index, " does not exist");
    if (texCoord < 0 || texCoord > 1) failAtPath(doc_, path + "/texCoord", "only TEXCOORD_0 and TEXCOORD_1 are supported, got ", texCoord);
    const tinygltf::Texture& t = doc_.model.textures[size_t(index)];
    const std::string tpath = strCat("/textures/", index);
    if (t.source < 0) failAtPath(doc_, tpath + "/source", "the texture has no image");
    if (size_t(t.source) >= doc_.model.images.size()) failAtPath(doc_, tpath + "/source", "image ", t.source, " does not exist");
    if (t.sampler >= 0 && size_t(t.sampler) >= doc_.model.samplers.size())
        failAtPath(doc_, tpath + "/sampler", "sampler ", t.sampler, " does not exist");
    return t;
}

TexturePtr MaterialCache::texture(int index, int texCoord, const tinygltf::ExtensionMap& ext, bool srgb, const std::string& path) {
    if (index < 0) return nullptr;
    const tinygltf::Texture& t = checkTexture(index, texCoord, path);
    Bitmap::Filter filter = Bitmap::Filter::Bilinear;
    Bitmap::Wrap wrap = Bitmap::Wrap::Repeat;
    if (t.sampler >= 0) {
        const tinygltf::Sampler& s = doc_.model.samplers[size_t(t.sampler)];
        if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) filter = Bitmap::Filter::Nearest;
        // One wrap mode for both axes (Bitmap's): wrapS (§5.26 sampler).
        if (s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) wrap = Bitmap::Wrap::Clamp;
        if (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) wrap = Bitmap::Wrap::Mirror;
    }
    TextureTransform tf;
    if (auto e = ext.find("KHR_texture_transform"); e != ext.end()) {
        const tinygltf::Value& v = e->second;
        auto pair = [&](const char* key, vec2 def) {
            if (!v.Has(key) || !v.Get(key).IsArray() || v.Get(key).ArrayLen() != 2) return def;
            return vec2(float(v.Get(key).Get(0).GetNumberAsDouble()), float(v.Get(key).Get(1).GetNumberAsDouble()));
        };
        tf.offset = pair("offset", vec2(0.0f));
        tf.scale = pair("scale", vec2(1.0f));
        tf.rotation = float(number(v, "rotation", 0.0));
        texCoord = integer(v, "texCoord", texCoord);  // the extension may override the set
        if (texCoord < 0 || texCoord > 1) failAtPath(doc_, path + "/extensions/KHR_texture_transform/texCoord", "only sets 0 and 1 are supported");
    }
    return std::make_shared<Texture>(image(t.source, srgb, strCat("/images/", t.source)), filter, wrap, texCoord, tf);
}

TexturePtr MaterialCache::texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& path) {
    return texture(info.index, info.texCoord, info.extensions, srgb, path);
}

TexturePtr MaterialCache::texture(const tinygltf::Value& ext, bool srgb, const std::string& path) {
    if (!ext.IsObject()) return nullptr;
    const int index = integer(ext, "index", -1);
    tinygltf::ExtensionMap nested;
    if (ext.Has("extensions") && ext.Get("extensions").IsObject()) {
        const tinygltf::Value& e = ext.Get("extensions");
        for (const std::string& k : e.Keys()) nested[k] = e.Get(k);
    }
    return texture(index, integer(ext, "texCoord", 0), nested, srgb, path);
}

ShapeMaterial MaterialCache::build(int index) {
    PbrParams p;
    ShapeMaterial out;
    p.rgbMode = parseThinFilmRGBMode(rgbMode_);
    if (index < 0) {  // §3.9.1: the default material (metallic 1, roughness 1, white)
        out.material = makePbrMaterial(p);
        return out;
    }
    if (size_t(index) >= doc_.model.materials.size()) failAtPath(doc_, "/materials", "material ", index, " does not exist");
    const tinygltf::Material& m = doc_.model.materials[size_t(index)];
    const std::string path = strCat("/materials/", index);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4) {
        p.baseColor.factor = vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
        p.baseAlpha.factor = float(pbr.baseColorFactor[3]);
    }
    p.baseColor.texture = p.baseAlpha.texture = texture(pbr.baseColorTexture, true, path + "/pbrMetallicRoughness/baseColorTexture");
    p.metallic.factor = float(pbr.metallicFactor);
    p.roughness.factor = float(pbr.roughnessFactor);
    p.metallic.texture = p.roughness.texture = texture(pbr.metallicRoughnessTexture, false, path + "/pbrMetallicRoughness/metallicRoughnessTexture");
    p.alphaMode = m.alphaMode == "MASK" ? AlphaMode::Mask : m.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    p.alphaCutoff = float(m.alphaCutoff);
    out.doubleSided = p.doubleSided = m.doubleSided;
    // §3.9.3 occlusionTexture: checked, not applied. It darkens indirect light as a rasterizer
    // approximates it; a path tracer integrates that light (and its occlusion) itself.
    if (m.occlusionTexture.index >= 0) checkTexture(m.occlusionTexture.index, m.occlusionTexture.texCoord, path + "/occlusionTexture");
    const std::string ext = path + "/extensions/";
    if (const auto* e = extension(m, "KHR_materials_ior")) {
        p.ior = float(number(*e, "ior", 1.5));
        if (!(p.ior >= 1.0f)) failAtPath(doc_, ext + "KHR_materials_ior/ior", "ior ", p.ior, " is not supported (need >= 1)");
    }
    if (const auto* e = extension(m, "KHR_materials_specular")) {
        p.specular.factor = float(number(*e, "specularFactor", 1.0));
        p.specular.texture = texture(e->Get("specularTexture"), false, ext + "KHR_materials_specular/specularTexture");
        p.specularColor.factor = color(*e, "specularColorFactor", vec3(1.0f));
        p.specularColor.texture = texture(e->Get("specularColorTexture"), true, ext + "KHR_materials_specular/specularColorTexture");
    }
    if (const auto* e = extension(m, "KHR_materials_transmission")) {
        p.transmission.factor = float(number(*e, "transmissionFactor", 0.0));
        p.transmission.texture = texture(e->Get("transmissionTexture"), false, ext + "KHR_materials_transmission/transmissionTexture");
    }
    if (const auto* e = extension(m, "KHR_materials_clearcoat")) {
        p.clearcoat.factor = float(number(*e, "clearcoatFactor", 0.0));
        p.clearcoat.texture = texture(e->Get("clearcoatTexture"), false, ext + "KHR_materials_clearcoat/clearcoatTexture");
        p.clearcoatRoughness.factor = float(number(*e, "clearcoatRoughnessFactor", 0.0));
        p.clearcoatRoughness.texture = texture(e->Get("clearcoatRoughnessTexture"), false, ext + "KHR_materials_clearcoat/clearcoatRoughnessTexture");
    }
    if (const auto* e = extension(m, "KHR_materials_sheen")) {
        p.sheenColor.factor = color(*e, "sheenColorFactor", vec3(0.0f));
        p.sheenColor.texture = texture(e->Get("sheenColorTexture"), true, ext + "KHR_materials_sheen/sheenColorTexture");
        p.sheenRoughness.factor = float(number(*e, "sheenRoughnessFactor", 0.0));
        p.sheenRoughness.texture = texture(e->Get("sheenRoughnessTexture"), false, ext + "KHR_materials_sheen/sheenRoughnessTexture");
    }
    if (const auto* e = extension(m, "KHR_materials_iridescence")) {
        p.iridescence.factor = float(number(*e, "iridescenceFactor", 0.0));
        p.iridescence.texture = texture(e->Get("iridescenceTexture"), false, ext + "KHR_materials_iridescence/iridescenceTexture");
        p.iridescenceIor = float(number(*e, "iridescenceIor", 1.3));
        if (!(p.iridescenceIor >= 1.0f)) failAtPath(doc_, ext + "KHR_materials_iridescence/iridescenceIor", "must be >= 1");
        p.thicknessMin = float(number(*e, "iridescenceThicknessMinimum", 100.0));
        p.thicknessMax = float(number(*e, "iridescenceThicknessMaximum", 400.0));
        p.thicknessTexture = texture(e->Get("iridescenceThicknessTexture"), false, ext + "KHR_materials_iridescence/iridescenceThicknessTexture");
    }
    if (const auto* e = extension(m, "KHR_materials_volume")) {
        const std::string vpath = ext + "KHR_materials_volume";
        const Volume v = readVolume(doc_, *e, vpath);
        if (e->Has("thicknessTexture") && e->Get("thicknessTexture").IsObject()) {  // for rasterizers: checked, not read
            const tinygltf::Value& t = e->Get("thicknessTexture");
            checkTexture(integer(t, "index", -1), integer(t, "texCoord", 0), vpath + "/thicknessTexture");
        }
        // A volume needs light to enter it: thickness > 0 on a transmitting material (README "Overview").
        if (v.thickness > 0 && (p.transmission.factor > 0 || p.transmission.texture)) {
            p.volume = true;
            out.interior = absorbingMedium(doc_, absorptionCoefficient(v, lengthScale_));
        }
    }
    out.material = makePbrMaterial(p);
    if (m.normalTexture.index >= 0) {  // §3.9.3 normalTexture: linear, perturbs the shading normal
        TexturePtr map = texture(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, false, path + "/normalTexture");
        out.material = makeNormalMapped(out.material, std::move(map), float(m.normalTexture.scale));
        out.normalMapped = true;
        out.normalTexCoord = m.normalTexture.texCoord;
    }
    // §3.9.3 emission, scaled by KHR_materials_emissive_strength.
    vec3 emissive(0.0f);
    if (m.emissiveFactor.size() == 3) emissive = vec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]);
    if (const auto* e = extension(m, "KHR_materials_emissive_strength")) emissive *= float(number(*e, "emissiveStrength", 1.0));
    if (emissive != vec3(0.0f)) {
        if (TexturePtr t = texture(m.emissiveTexture, true, path + "/emissiveTexture"))
            out.emissionTexture = std::make_shared<EmissionTexture>(emissive, std::move(t));
        else
            out.emission = makeRGBSpectrum(glm::max(emissive, vec3(0.0f)), SpectrumKind::Illuminant);
    }
    return out;
}

}  // namespace iris::gltf
