#include "materials/textures/bitmap.h"

#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <tuple>

#include "core/xml/xml_values.h"
#include "core/srgb_transfer.h"

namespace iris {

Bitmap::Bitmap(Image img) : img_(std::move(img)) {
    if (img_.width <= 0 || img_.height <= 0 || img_.channels <= 0 ||
        img_.pixels.size() != img_.pixelCount() * size_t(img_.channels))
        fail("bitmap: invalid image (", img_.width, "x", img_.height, "x", img_.channels, ")");
}

std::shared_ptr<const Bitmap> Bitmap::load(const std::string& path, bool raw, bool fp16) {
    // Textures reading the same file (e.g. a colour and a roughness from one image) share it.
    static std::mutex mutex;
    static std::map<std::tuple<std::string, bool, bool>, std::weak_ptr<const Bitmap>> cache;
    const auto key = std::make_tuple(path, raw, fp16);
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (auto hit = cache[key].lock()) return hit;
    }
    std::shared_ptr<const Bitmap> b = loadUncached(path, raw, fp16);
    std::lock_guard<std::mutex> lock(mutex);
    cache[key] = b;
    return b;
}

float Bitmap::roundToHalf(float x) {
    if (!std::isfinite(x) || x == 0.0f) return x;
    const float a = std::abs(x);
    int e = 0;
    std::frexp(a, &e);  // a = m·2^e, m ∈ [0.5, 1): the leading bit has weight 2^(e−1)
    // binary16: 10 fraction bits, normal exponents from −14; below that the spacing is 2^−24.
    const float quantum = std::ldexp(1.0f, std::max(e - 11, -24));
    float r = std::nearbyint(a / quantum) * quantum;  // exact scaling; nearbyint: ties to even
    if (r > 65504.0f) r = std::numeric_limits<float>::infinity();
    return std::copysign(r, x);
}

std::shared_ptr<const Bitmap> Bitmap::loadUncached(const std::string& path, bool raw, bool fp16) {
    ImageFileInfo info;
    Image img = readImage(path, &info);
    if (!raw) {
        const std::string& cs = info.colorSpace;
        const bool integer = info.integerFormat;
        const bool linearTag = cs == "Linear" || cs == "linear" || cs == "lin_srgb" || cs == "scene_linear";
        if (integer && !linearTag) {
            // Decode colour channels, never alpha (channel 1 of grey+alpha, channel 3 of RGBA).
            const int colour = img.channels == 2 ? 1 : std::min(img.channels, 3);
            for (size_t p = 0; p < img.pixelCount(); ++p)
                for (int c = 0; c < colour; ++c) {
                    float& v = img.pixels[p * size_t(img.channels) + size_t(c)];
                    v = srgbToLinear(v);
                }
        }
    }
    if (fp16)
        for (float& v : img.pixels) v = roundToHalf(v);
    try {
        return std::make_shared<const Bitmap>(std::move(img));
    } catch (const Error& e) {
        fail(path, ": ", e.what());
    }
}

int Bitmap::wrap(int i, int n, Wrap w) const {
    switch (w) {
        case Wrap::Clamp: return std::clamp(i, 0, n - 1);
        case Wrap::Repeat: {
            const int r = i % n;
            return r < 0 ? r + n : r;
        }
        case Wrap::Mirror: {
            int r = i % (2 * n);
            if (r < 0) r += 2 * n;
            return r < n ? r : 2 * n - 1 - r;
        }
    }
    return 0;
}

vec2 Bitmap::sanitise(const vec2& uvIn, Wrap w) {
    // Keep huge or non-finite coordinates from overflowing int conversions.
    vec2 uv = uvIn;
    for (int k = 0; k < 2; ++k) {
        if (!std::isfinite(uv[k])) uv[k] = 0.0f;
        if (w == Wrap::Repeat || w == Wrap::Mirror) uv[k] -= 2.0f * std::floor(uv[k] * 0.5f);  // periods of 1 and 2
        uv[k] = std::clamp(uv[k], -4.0f, 4.0f);
    }
    return uv;
}

Bitmap::Footprint Bitmap::footprint(const vec2& uvIn, Filter f, Wrap w) const {
    Footprint fp;
    const int W = img_.width, H = img_.height;
    const vec2 uv = sanitise(uvIn, w);
    const float x = uv.x * float(W), y = uv.y * float(H);
    if (f == Filter::Nearest) {
        const int xi = wrap(int(std::floor(x)), W, w), yi = wrap(int(std::floor(y)), H, w);
        fp.count = 1;
        fp.texel[0] = size_t(yi) * size_t(W) + size_t(xi);
        fp.weight[0] = 1.0f;
        return fp;
    }
    const Cell c = bilinearCell(uv, w);
    fp.count = 4;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            fp.texel[j * 2 + i] = size_t(c.ys[j]) * size_t(W) + size_t(c.xs[i]);
            fp.weight[j * 2 + i] = (i ? c.tx : 1.0f - c.tx) * (j ? c.ty : 1.0f - c.ty);
        }
    return fp;
}

Bitmap::Cell Bitmap::bilinearCell(const vec2& uv, Wrap w) const {
    const int W = img_.width, H = img_.height;
    const float x = uv.x * float(W), y = uv.y * float(H);
    const float px = x - 0.5f, py = y - 0.5f;  // texel centres at half-integers
    const float fx = std::floor(px), fy = std::floor(py);
    const int x0 = int(fx), y0 = int(fy);
    return Cell{{wrap(x0, W, w), wrap(x0 + 1, W, w)}, {wrap(y0, H, w), wrap(y0 + 1, H, w)}, px - fx, py - fy};
}

float Bitmap::texelGrey(size_t t) const {
    const vec3 c = texelRGB(t);
    return img_.channels < 3 ? c.x : (c.x + c.y + c.z) / 3.0f;
}

vec2 Bitmap::gradientGrey(const vec2& uvIn, Filter f, Wrap w) const {
    if (f == Filter::Nearest) return vec2(0.0f);
    const Cell c = bilinearCell(sanitise(uvIn, w), w);
    const size_t W = size_t(img_.width);
    auto g = [&](int i, int j) { return texelGrey(size_t(c.ys[j]) * W + size_t(c.xs[i])); };
    const float g00 = g(0, 0), g10 = g(1, 0), g01 = g(0, 1), g11 = g(1, 1);
    const float dx = (1.0f - c.ty) * (g10 - g00) + c.ty * (g11 - g01);
    const float dy = (1.0f - c.tx) * (g01 - g00) + c.tx * (g11 - g10);
    return vec2(float(img_.width) * dx, float(img_.height) * dy);  // pixel → uv units
}

vec3 Bitmap::texelRGB(size_t t) const {
    if (img_.channels < 3) return vec3(texel(t, 0));
    return vec3(texel(t, 0), texel(t, 1), texel(t, 2));
}

vec3 Bitmap::lookupRGB(const vec2& uv, Filter f, Wrap w) const {
    const Footprint fp = footprint(uv, f, w);
    vec3 c(0.0f);
    for (int i = 0; i < fp.count; ++i) c += fp.weight[i] * texelRGB(fp.texel[i]);
    return c;
}

float Bitmap::lookupGrey(const vec2& uv, Filter f, Wrap w) const {
    const vec3 c = lookupRGB(uv, f, w);
    return img_.channels < 3 ? c.x : (c.x + c.y + c.z) / 3.0f;
}

Bitmap::Filter Bitmap::parseFilter(const std::string& s, const SourceLocation& loc) {
    if (s == "bilinear") return Filter::Bilinear;
    if (s == "nearest") return Filter::Nearest;
    // Mitsuba 0.6's mipmapped filters: approximated by bilinear (no mipmaps here).
    if (s == "ewa" || s == "trilinear") return Filter::Bilinear;
    failAt(loc, "filter_type '", s, "' is not supported (supported: bilinear, nearest; 0.6's ewa and trilinear act as bilinear)");
}

Bitmap::Wrap Bitmap::parseWrap(const std::string& s, const SourceLocation& loc) {
    if (s == "repeat") return Wrap::Repeat;
    if (s == "mirror") return Wrap::Mirror;
    if (s == "clamp") return Wrap::Clamp;
    failAt(loc, "wrap_mode '", s, "' is not supported (supported: repeat, mirror, clamp)");
}

}  // namespace iris
