#include "render/loader/gltf_volume.h"

#include <cmath>

namespace iris::gltf {

Volume readVolume(const Document& doc, const tinygltf::Value& ext, const std::string& path) {
    Volume v;
    if (!ext.IsObject()) failAtPath(doc, path, "must be an object");
    auto number = [&](const char* key) -> std::optional<double> {
        if (!ext.Has(key)) return std::nullopt;
        const tinygltf::Value& x = ext.Get(key);
        if (!x.IsNumber()) failAtPath(doc, path + "/" + key, "must be a number");
        return x.GetNumberAsDouble();
    };
    if (auto t = number("thicknessFactor")) {
        if (!(*t >= 0) || !std::isfinite(*t)) failAtPath(doc, path + "/thicknessFactor", "must be >= 0, got ", *t);
        v.thickness = float(*t);
    }
    if (auto d = number("attenuationDistance")) {
        if (!(*d > 0)) failAtPath(doc, path + "/attenuationDistance", "must be > 0, got ", *d);
        v.attenuationDistance = float(*d);
    }
    if (ext.Has("attenuationColor")) {
        const tinygltf::Value& c = ext.Get("attenuationColor");
        if (!c.IsArray() || c.ArrayLen() != 3) failAtPath(doc, path + "/attenuationColor", "must be an array of three numbers");
        for (int i = 0; i < 3; ++i) {
            const tinygltf::Value& x = c.Get(i);
            const double value = x.IsNumber() ? x.GetNumberAsDouble() : -1.0;
            if (!x.IsNumber() || !(value >= 0 && value <= 1))
                failAtPath(doc, strCat(path, "/attenuationColor/", i), "must be a number in [0, 1]");
            v.attenuationColor[i] = float(value);
        }
    }
    return v;
}

vec3 absorptionCoefficient(const Volume& v, float lengthScale) {
    vec3 sigma(0.0f);
    if (std::isinf(v.attenuationDistance)) return sigma;
    for (int i = 0; i < 3; ++i) {
        const float c = std::max(v.attenuationColor[i], 1e-30f);
        sigma[i] = -std::log(c) / (v.attenuationDistance * lengthScale);  // README "Attenuation": σ_t = −log(c) / d
    }
    return glm::max(sigma, vec3(0.0f));
}

MediumPtr absorbingMedium(const Document& doc, const vec3& sigmaA) {
    if (sigmaA == vec3(0.0f)) return nullptr;
    const SourceLocation loc{doc.path, 0};
    Properties p("medium", "homogeneous", loc);
    p.set("sigma_a", RGBValue{sigmaA}, loc);  // upsampled in spectral mode as an XML <rgb name="sigma_a">
    p.set("sigma_s", 0.0f, loc);
    return MediumRegistry::instance().create(p);
}

}  // namespace iris::gltf
