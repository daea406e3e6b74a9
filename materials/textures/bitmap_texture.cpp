// The `bitmap` texture (Mitsuba): an image looked up at the surface uv. Parameters: filename,
// raw (false: 8/16-bit images are sRGB-decoded), filter_type (bilinear | nearest), wrap_mode
// (repeat | mirror | clamp), to_uv, format (auto | variant | fp16: storage precision), accel
// (accepted, no effect). As a spectrum texture in RGB mode it returns the filtered
// texel RGB unchanged; in spectral mode each texel's RGB is upsampled and the texels' spectra are
// interpolated with the filter weights (as Mitsuba 3 does). Small images (at most
// kMaxPerTexelFits texels) fit one sigmoid per texel, lazily on the first spectral lookup (≈ 34 µs
// each); larger ones use the shared RGBSpectrumGrid (17³ node fits, built once per process, then
// interpolated: the projection back to RGB stays exact, spectral/rgb_spectrum_grid.h).
#include <mutex>

#include "core/registry.h"
#include "materials/textures/bitmap.h"
#include "materials/textures/texture.h"
#include "materials/textures/uv_transform.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/rgb_spectrum_grid.h"
#include "spectral/spectrum_factory.h"

namespace iris {
namespace {

constexpr size_t kMaxPerTexelFits = size_t(RGBSpectrumGrid::kResolution) * RGBSpectrumGrid::kResolution *
                                    RGBSpectrumGrid::kResolution;

struct BitmapParams {
    std::shared_ptr<const Bitmap> bitmap;
    Bitmap::Filter filter;
    Bitmap::Wrap wrap;

    explicit BitmapParams(const Properties& p) {
        const std::string file = p.getString("filename");
        const bool raw = p.getBool("raw", false);
        filter = Bitmap::parseFilter(p.getString("filter_type", "bilinear"), p.locationOf("filter_type"));
        wrap = Bitmap::parseWrap(p.getString("wrap_mode", "repeat"), p.locationOf("wrap_mode"));
        const bool fp16 = parseFormat(p);
        p.getBool("accel", true);  // Mitsuba 3: CUDA hardware interpolation; no effect on the CPU
        bitmap = withLocation(p.locationOf("filename"), [&] { return Bitmap::load(file, raw, fp16); });
    }

    /// Mitsuba 3's storage `format` (src/textures/bitmap.cpp): "auto" (default), "variant" or
    /// "fp16"; true for fp16 (texels rounded to half precision). "auto" stores 8/16-bit images as
    /// half in Mitsuba's RGB variants and as the variant's float in spectral ones; iris keeps
    /// float (the render mode is not known when the scene loads; the rounding, a relative 2^-11 at
    /// most, is far below the noise of a conformance render).
    static bool parseFormat(const Properties& p) {
        const std::string f = p.getString("format", "auto");
        if (f == "auto" || f == "variant") return false;
        if (f == "fp16") return true;
        failAt(p.locationOf("format"), "bitmap: format '", f, "' is not supported (supported: auto, variant, fp16)");
    }
};

class BitmapSpectrumTexture final : public SpectrumTexture {
public:
    BitmapSpectrumTexture(const Properties& p, SpectrumKind kind) : params_(p), uv_(p), kind_(kind) {}

    SampledSpectrum eval(const TextureQuery& q, const SampledWavelengths& wl) const override {
        const vec2 uv = uv_.apply(q.uv);
        const Bitmap& b = *params_.bitmap;
        if (wl.isRGB()) {
            const vec3 c = b.lookupRGB(uv, params_.filter, params_.wrap);
            SampledSpectrum s(3);
            for (int i = 0; i < 3; ++i) s[i] = c[i];
            return s;
        }
        const Bitmap::Footprint fp = b.footprint(uv, params_.filter, params_.wrap);
        SampledSpectrum s(wl.size());
        if (size_t(b.width()) * size_t(b.height()) > kMaxPerTexelFits) {
            const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();
            for (int i = 0; i < fp.count; ++i)
                if (fp.weight[i] > 0) s += fp.weight[i] * grid.sample(b.texelRGB(fp.texel[i]), kind_, wl);
            return s;
        }
        std::call_once(once_, [&] {
            spectra_.reserve(size_t(b.width()) * size_t(b.height()));
            for (size_t t = 0; t < size_t(b.width()) * size_t(b.height()); ++t) spectra_.emplace_back(b.texelRGB(t), kind_);
        });
        for (int i = 0; i < fp.count; ++i)
            if (fp.weight[i] > 0) s += fp.weight[i] * spectra_[fp.texel[i]].sample(wl);
        return s;
    }

    ivec2 resolution() const override { return ivec2(params_.bitmap->width(), params_.bitmap->height()); }

private:
    BitmapParams params_;
    UVTransform uv_;
    SpectrumKind kind_;
    mutable std::once_flag once_;
    mutable std::vector<RGBSpectrum> spectra_;
};

class BitmapFloatTexture final : public FloatTexture {
public:
    explicit BitmapFloatTexture(const Properties& p) : params_(p), uv_(p) {}
    float eval(const TextureQuery& q) const override {
        return params_.bitmap->lookupGrey(uv_.apply(q.uv), params_.filter, params_.wrap);
    }
    /// The bilinear interpolant's exact derivative (Mitsuba 3 eval_1_grad), pulled back through
    /// the uv transform: ∇_uv g = Jᵀ ∇_uv' g with J = ∂uv'/∂uv (chain rule).
    vec2 gradient(const TextureQuery& q, float) const override {
        return uv_.pullBack(params_.bitmap->gradientGrey(uv_.apply(q.uv), params_.filter, params_.wrap));
    }

private:
    BitmapParams params_;
    UVTransform uv_;
};

std::shared_ptr<SpectrumTexture> createSpectrum(const Properties& p, SpectrumKind kind) {
    return std::make_shared<BitmapSpectrumTexture>(p, kind);
}
std::shared_ptr<FloatTexture> createFloat(const Properties& p) { return std::make_shared<BitmapFloatTexture>(p); }

}  // namespace

IRIS_REGISTER(SpectrumTextureRegistry, "bitmap", createSpectrum);
IRIS_REGISTER(FloatTextureRegistry, "bitmap", createFloat);

}  // namespace iris
