// Latitude-longitude HDR environment map (Mitsuba 3 "envmap"), importance sampled by texel
// luminance × sinθ (pbrt-v4 §12.5.2). Direction convention (Mitsuba 3): in the light's frame,
// θ is measured from +y, φ = atan2(x, −z); u = φ/2π, v = θ/π.
//
// Spectral mode: texel RGB (linear Rec.709) becomes an illuminant spectrum. Solving the
// RGB→spectrum fit per texel would cost seconds, so the map's chromaticities c = rgb/max(rgb)
// are located in a 17³ grid whose corner spectra are fitted lazily (only corners the map uses,
// once, on the first spectral lookup) and interpolated trilinearly. Because the RGB projection is
// linear in the spectrum, the interpolated spectrum still projects exactly to the texel's RGB
// (up to the corners' own fitting error).
#include <mutex>

#include "core/io/image.h"
#include "render/lights/light.h"
#include "core/registry.h"
#include "core/sampling.h"
#include "spectral/rgb_spectrum.h"

namespace iris {
namespace {

constexpr int kGrid = 17;

class EnvMapLight final : public Light {
public:
    EnvMapLight(Image img, const mat4& toWorld, float scale, std::string name)
        : img_(std::move(img)), toWorld_(toWorld), toLocal_(glm::inverse(mat3(toWorld))), scale_(scale), name_(std::move(name)) {
        const int w = img_.width, h = img_.height;
        rgb_.resize(size_t(w) * h);
        std::vector<float> weight(size_t(w) * h);
        for (int y = 0; y < h; ++y) {
            const float sinTheta = std::sin(kPi * (y + 0.5f) / h);
            for (int x = 0; x < w; ++x) {
                vec3 c(0.0f);
                for (int k = 0; k < std::min(3, img_.channels); ++k) c[k] = img_.at(x, y, k);
                if (img_.channels == 1) c = vec3(c.x);
                c = glm::max(c, vec3(0.0f));
                if (!isFinite(c)) c = vec3(0.0f);
                rgb_[size_t(y) * w + x] = c * scale_;
                // Luminance (Rec.709 Y) × sinθ; a small floor keeps every direction samplable.
                weight[size_t(y) * w + x] = (0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z + 1e-6f) * sinTheta;
            }
        }
        dist_ = Distribution2D(weight, w, h);
        img_.pixels.clear();
        img_.pixels.shrink_to_fit();
    }

    Type type() const override { return Type::Infinite; }

    std::optional<LightSample> sampleLi(const vec3&, const vec2& u, const SampledWavelengths& wl) const override {
        float mapPdf;
        const vec2 uv = dist_.sampleContinuous(u, &mapPdf);
        if (mapPdf <= 0) return std::nullopt;
        const float theta = uv.y * kPi, phi = uv.x * 2.0f * kPi;
        const float sinTheta = std::sin(theta);
        if (sinTheta <= 0) return std::nullopt;
        const vec3 local(sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi));
        LightSample ls;
        ls.wi = glm::normalize(mat3(toWorld_) * local);
        ls.pdf = mapPdf / (2.0f * kPi * kPi * sinTheta);
        ls.infinite = true;
        ls.L = lookup(uv, wl);
        return ls;
    }

    float pdfLi(const vec3&, const vec3& wi, const SurfaceInteraction*) const override {
        const vec3 v = glm::normalize(toLocal_ * wi);
        const float sinTheta = safeSqrt(1.0f - v.y * v.y);
        if (sinTheta <= 0) return 0.0f;
        return dist_.pdf(dirToUV(v)) / (2.0f * kPi * kPi * sinTheta);
    }

    SampledSpectrum Le(const vec3&, const vec3&, const vec3& w, const SampledWavelengths& wl) const override {
        return lookup(dirToUV(glm::normalize(toLocal_ * w)), wl);
    }

private:
    static vec2 dirToUV(const vec3& v) {
        float u = std::atan2(v.x, -v.z) * kInv2Pi;
        if (u < 0) u += 1.0f;
        return vec2(u, safeAcos(v.y) * kInvPi);
    }

    vec3 texel(const vec2& uv) const {
        // Nearest texel: the sampling density is piecewise constant per texel, so Le and pdf agree.
        const int x = std::clamp(int(uv.x * img_.width), 0, img_.width - 1);
        const int y = std::clamp(int(uv.y * img_.height), 0, img_.height - 1);
        return rgb_[size_t(y) * img_.width + x];
    }

    SampledSpectrum lookup(const vec2& uv, const SampledWavelengths& wl) const {
        const vec3 c = texel(uv);
        SampledSpectrum s(wl.size());
        if (wl.isRGB()) {
            for (int i = 0; i < 3; ++i) s[i] = c[i];
            return s;
        }
        const float m = std::max({c.x, c.y, c.z});
        if (m <= 0) return s;
        std::call_once(gridOnce_, [this] { buildGrid(); });
        const vec3 g = c / m * float(kGrid - 1);
        const int x0 = std::min(int(g.x), kGrid - 2), y0 = std::min(int(g.y), kGrid - 2), z0 = std::min(int(g.z), kGrid - 2);
        const vec3 f = g - vec3(x0, y0, z0);
        // Every corner is an Illuminant RGBSpectrum, eval = shape(λ) · k · D65(λ) with the same k,
        // so the trilinear sum of the shapes is taken first and k · D65(λ) applied once (linearity;
        // the result differs from summing the corners' eval only by float rounding). The corners
        // are called directly (RGBSpectrum is final), not through the virtual Spectrum::eval.
        const int n = wl.size();
        float acc[kMaxWavelengths];
        for (int i = 0; i < n; ++i) acc[i] = 0.0f;
        for (int corner = 0; corner < 8; ++corner) {
            const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
            const float w = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
            if (w <= 0) continue;
            const RGBSpectrum& sp = *grid_[gridIndex(x0 + dx, y0 + dy, z0 + dz)];
            if (sp.isGrey()) {
                const float v = sp.shapeValue(kLambdaMin);
                for (int i = 0; i < n; ++i) acc[i] += w * v;
            } else {
                for (int i = 0; i < n; ++i) acc[i] += w * sp.shapeValue(wl.lambda(i));
            }
        }
        const float* d65 = wl.d65Lanes();  // cie::d65 at the path's wavelengths, computed at sampling
        for (int i = 0; i < n; ++i) s[i] = acc[i] * (d65Factor_ * d65[i]);
        return s * m;
    }

    static int gridIndex(int x, int y, int z) { return (z * kGrid + y) * kGrid + x; }

    void buildGrid() const {
        // Fit only the corners of cells that some texel uses.
        std::vector<char> needed(kGrid * kGrid * kGrid, 0);
        for (const vec3& c : rgb_) {
            const float m = std::max({c.x, c.y, c.z});
            if (m <= 0) continue;
            const vec3 g = c / m * float(kGrid - 1);
            const int x0 = std::min(int(g.x), kGrid - 2), y0 = std::min(int(g.y), kGrid - 2), z0 = std::min(int(g.z), kGrid - 2);
            for (int corner = 0; corner < 8; ++corner)
                needed[gridIndex(x0 + (corner & 1), y0 + ((corner >> 1) & 1), z0 + ((corner >> 2) & 1))] = 1;
        }
        grid_.resize(needed.size());
        for (int z = 0; z < kGrid; ++z)
            for (int y = 0; y < kGrid; ++y)
                for (int x = 0; x < kGrid; ++x)
                    if (needed[gridIndex(x, y, z)]) {
                        // The spectrum makeRGBSpectrum(rgb, Illuminant) returns, held by its type.
                        grid_[gridIndex(x, y, z)] = std::make_unique<RGBSpectrum>(vec3(x, y, z) / float(kGrid - 1), SpectrumKind::Illuminant);
                        d65Factor_ = grid_[gridIndex(x, y, z)]->d65Factor();
                    }
    }

    Image img_;  // size only (pixels released after construction)
    std::vector<vec3> rgb_;
    mat4 toWorld_;
    mat3 toLocal_;
    float scale_;
    std::string name_;
    Distribution2D dist_;
    mutable std::once_flag gridOnce_;
    mutable std::vector<std::unique_ptr<const RGBSpectrum>> grid_;
    mutable float d65Factor_ = 0;  // the corners' common D65 normalisation (RGBSpectrum::d65Factor)
};

std::shared_ptr<Light> createEnvMap(const Properties& p) {
    const std::string file = p.getString("filename");
    Image img = withLocation(p.locationOf("filename"), [&] { return readImage(file); });
    if (img.width < 1 || img.height < 1) failAt(p.locationOf("filename"), file, ": empty environment map");
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0) || !std::isfinite(scale)) failAt(p.locationOf("scale"), "envmap scale must be a finite value >= 0");
    return std::make_shared<EnvMapLight>(std::move(img), p.getTransform("to_world"), scale, file);
}

}  // namespace

IRIS_REGISTER(LightRegistry, "envmap", createEnvMap);

}  // namespace iris
