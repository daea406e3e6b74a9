// Latitude-longitude HDR environment map (Mitsuba "envmap"). Direction convention (Mitsuba): in
// the light's frame, θ is measured from +y, φ = atan2(x, −z); u = φ/2π, v = θ/π.
//
// Radiance is interpolated bilinearly between texels placed as the scene's format version says
// (render/lights/envmap_lattice.h: Mitsuba 0.6 for version 0.x files, Mitsuba 3 otherwise).
// Directions are importance sampled from a piecewise-constant density over a grid of cells in
// (u, v) (pbrt-v4 §12.5.2), each weighted by the exact cell average of the interpolated luminance
// × sinθ at the cell centre: a cell whose average is zero has zero radiance everywhere (the
// interpolant is non-negative), and a small floor keeps every direction samplable, so sampleLi and
// pdfLi are one density and the estimator stays unbiased with MIS.
//
// Spectral mode: texel RGB (linear Rec.709) becomes an illuminant spectrum. Solving the
// RGB→spectrum fit per texel would cost seconds, so the map's chromaticities c = rgb/max(rgb)
// are located in a 17³ grid whose corner spectra are fitted lazily (only corners the map uses,
// once, on the first spectral lookup) and interpolated trilinearly. Because the RGB projection is
// linear in the spectrum, the interpolated spectrum still projects exactly to the texel's RGB
// (up to the corners' own fitting error). Between texels, spectra are interpolated as the
// version's Mitsuba does (see lookup()).
#include <mutex>

#include "core/io/image.h"
#include "render/lights/envmap_lattice.h"
#include "render/lights/light.h"
#include "core/registry.h"
#include "core/sampling.h"
#include "spectral/rgb_spectrum.h"

namespace iris {
namespace {

constexpr int kGrid = 17;

class EnvMapLight final : public Light {
public:
    EnvMapLight(Image img, const EnvmapLattice& lattice, const mat4& toWorld, float scale, std::string name)
        : img_(std::move(img)), lattice_(lattice), toWorld_(toWorld), toLocal_(glm::inverse(mat3(toWorld))), scale_(scale), name_(std::move(name)) {
        const int w = img_.width, h = img_.height;
        rgb_.resize(size_t(w) * h);
        std::vector<float> luminance(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                vec3 c(0.0f);
                for (int k = 0; k < std::min(3, img_.channels); ++k) c[k] = img_.at(x, y, k);
                if (img_.channels == 1) c = vec3(c.x);
                c = glm::max(c, vec3(0.0f));
                if (!isFinite(c)) c = vec3(0.0f);
                rgb_[size_t(y) * w + x] = c * scale_;
                luminance[size_t(y) * w + x] = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;  // Rec.709 Y
            }
        buildDistribution(luminance);
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

    SampledSpectrum Le(const TextureQuery&, const vec3&, const vec3& w, const SampledWavelengths& wl) const override {
        return lookup(dirToUV(glm::normalize(toLocal_ * w)), wl);
    }

private:
    static vec2 dirToUV(const vec3& v) {
        float u = std::atan2(v.x, -v.z) * kInv2Pi;
        if (u < 0) u += 1.0f;
        return vec2(u, safeAcos(v.y) * kInvPi);
    }

    /// The four texels around uv and their bilinear weights (envmap_lattice.h).
    struct Taps {
        int index[4];
        float weight[4];
    };
    Taps taps(const vec2& uv) const {
        int x0, x1, y0, y1;
        float fx, fy;
        lattice_.u.taps(uv.x, x0, x1, fx);
        lattice_.v.taps(uv.y, y0, y1, fy);
        const int w = img_.width;
        return {{y0 * w + x0, y0 * w + x1, y1 * w + x0, y1 * w + x1},
                {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy}};
    }

    /// Sampling weights: per cell of the (u.texels × cellsV) grid, the exact average of the
    /// bilinear luminance over the cell × sinθ at its centre, plus a floor.
    void buildDistribution(const std::vector<float>& luminance) {
        const int nu = lattice_.u.texels, nv = lattice_.cellsV, w = img_.width;
        std::vector<float> weight(size_t(nu) * nv);
        for (int j = 0; j < nv; ++j) {
            const float sinTheta = std::sin(kPi * (j + 0.5f) / nv);
            for (int i = 0; i < nu; ++i) {
                double avg = 0;
                forEachAverageWeight(lattice_.v, double(j) / nv, double(j + 1) / nv, [&](int ty, double wy) {
                    forEachAverageWeight(lattice_.u, double(i) / nu, double(i + 1) / nu,
                                         [&](int tx, double wx) { avg += wy * wx * luminance[size_t(ty) * w + tx]; });
                });
                weight[size_t(j) * nu + i] = (float(avg) + 1e-6f) * sinTheta;
            }
        }
        dist_ = Distribution2D(weight, nu, nv);
    }

    SampledSpectrum lookup(const vec2& uv, const SampledWavelengths& wl) const {
        const Taps t = taps(uv);
        SampledSpectrum s(wl.size());
        if (wl.isRGB()) {
            vec3 c(0.0f);
            for (int k = 0; k < 4; ++k) c += t.weight[k] * rgb_[t.index[k]];
            for (int i = 0; i < 3; ++i) s[i] = c[i];
            return s;
        }
        // Texel k has spectrum m_k · S(c_k) (scale m_k = max component, chromaticity c_k).
        // Mitsuba 0.6 interpolates the texels' spectra: Σ w_k m_k S(c_k). Mitsuba 3 interpolates
        // the normalised spectra and the scales separately and multiplies them (eval_spectrum:
        // s = Σ w_k S_k, f = Σ w_k f_k, result s · f), which differs at edges between bright and
        // dark texels (its spectral references differ there from its RGB ones).
        const int n = wl.size();
        float acc[kMaxWavelengths];
        for (int i = 0; i < n; ++i) acc[i] = 0.0f;
        float scale = 0.0f;
        for (int k = 0; k < 4; ++k) {
            if (t.weight[k] <= 0) continue;
            const vec3& c = rgb_[t.index[k]];
            const float m = std::max({c.x, c.y, c.z});
            if (m <= 0) continue;
            addChromaticityShape(c / m, t.weight[k] * (lattice_.separateScale ? 1.0f : m), wl, acc);
            scale += t.weight[k] * m;
        }
        if (scale <= 0) return s;
        const float common = d65Factor_ * (lattice_.separateScale ? scale : 1.0f);
        const float* d65 = wl.d65Lanes();  // cie::d65 at the path's wavelengths, computed at sampling
        for (int i = 0; i < n; ++i) s[i] = acc[i] * (common * d65[i]);
        return s;
    }

    /// acc += weight · Σ_corners w_c · shape_c(λ) for the chromaticity (max component 1).
    void addChromaticityShape(const vec3& chroma, float weight, const SampledWavelengths& wl, float* acc) const {
        std::call_once(gridOnce_, [this] { buildGrid(); });
        const vec3 g = chroma * float(kGrid - 1);
        const int x0 = std::min(int(g.x), kGrid - 2), y0 = std::min(int(g.y), kGrid - 2), z0 = std::min(int(g.z), kGrid - 2);
        const vec3 f = g - vec3(x0, y0, z0);
        // Every corner is an Illuminant RGBSpectrum, eval = shape(λ) · k · D65(λ) with the same k,
        // so the trilinear sum of the shapes is taken first and k · D65(λ) applied once (linearity;
        // the result differs from summing the corners' eval only by float rounding). The corners
        // are called directly (RGBSpectrum is final), not through the virtual Spectrum::eval.
        const int n = wl.size();
        for (int corner = 0; corner < 8; ++corner) {
            const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
            const float w = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z) * weight;
            if (w <= 0) continue;
            const RGBSpectrum& sp = *grid_[gridIndex(x0 + dx, y0 + dy, z0 + dz)];
            if (sp.isGrey()) {
                const float v = sp.shapeValue(kLambdaMin);
                for (int i = 0; i < n; ++i) acc[i] += w * v;
            } else {
                for (int i = 0; i < n; ++i) acc[i] += w * sp.shapeValue(wl.lambda(i));
            }
        }
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
    EnvmapLattice lattice_;
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
    // Texel placement by format version (docs/scene_format.md): Mitsuba 3 puts the first and last
    // rows on the poles and, like Mitsuba 3, needs at least 2×3 texels; Mitsuba 0.6 any size.
    const bool mitsuba3 = p.formatVersion() >= 2;
    if (img.width < 1 || img.height < 1) failAt(p.locationOf("filename"), file, ": empty environment map");
    if (mitsuba3 && (img.width < 2 || img.height < 3))
        failAt(p.locationOf("filename"), file, ": an environment map of a version ", p.formatVersion(),
               " scene needs at least 2x3 pixels (Mitsuba 3's rule), this one is ", img.width, "x", img.height);
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0) || !std::isfinite(scale)) failAt(p.locationOf("scale"), "envmap scale must be a finite value >= 0");
    const EnvmapLattice lattice = mitsuba3 ? EnvmapLattice::mitsuba3(img.width, img.height) : EnvmapLattice::mitsuba06(img.width, img.height);
    return std::make_shared<EnvMapLight>(std::move(img), lattice, p.getTransform("to_world"), scale, file);
}

}  // namespace

IRIS_REGISTER(LightRegistry, "envmap", createEnvMap);

}  // namespace iris
