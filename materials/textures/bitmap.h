// A texture image with wrapped, filtered lookups (used by the `bitmap` texture and reusable by
// normal/bump-map wrappers). Coordinates follow Mitsuba: u to the right, v down from the top row
// (u, v) ∈ [0,1]²; texel centres at ((x + 0.5)/w, (y + 0.5)/h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/image.h"
#include "core/math.h"

namespace iris {

class Bitmap {
public:
    enum class Filter { Nearest, Bilinear };
    enum class Wrap { Repeat, Mirror, Clamp };

    /// Up to four texels and their weights (summing to 1) for one lookup.
    struct Footprint {
        int count = 0;
        size_t texel[4] = {0, 0, 0, 0};  // y * width + x
        float weight[4] = {0, 0, 0, 0};
    };

    explicit Bitmap(Image img);

    /// Read with readImage (core/image.h: OpenEXR, or the OpenImageIO module). Unless `raw`, integer (8/16-bit) images not tagged as linear are
    /// decoded from sRGB to linear (Mitsuba's behaviour); float images are used as stored.
    /// With `fp16` every (decoded) value is then rounded to the nearest half-precision float, as
    /// Mitsuba 3's bitmap stores it with format="fp16" (src/textures/bitmap.cpp: the image is
    /// converted to dr::half after the sRGB decoding).
    /// Errors name the file. Files already loaded (and still in use) with the same `raw` and
    /// `fp16` are shared.
    static std::shared_ptr<const Bitmap> load(const std::string& path, bool raw, bool fp16 = false);
    /// The same without the cache (always reads the file).
    static std::shared_ptr<const Bitmap> loadUncached(const std::string& path, bool raw, bool fp16 = false);
    /// x rounded to the nearest IEEE 754 binary16 value (ties to even; beyond the largest finite
    /// half, 65504, values from 65520 up become infinite; NaN stays NaN).
    static float roundToHalf(float x);

    int width() const { return img_.width; }
    int height() const { return img_.height; }
    int channels() const { return img_.channels; }
    const Image& image() const { return img_; }

    /// Which texels a lookup at uv touches, with their weights.
    Footprint footprint(const vec2& uv, Filter f, Wrap w) const;
    /// Channel c of texel index t (as in Footprint::texel).
    float texel(size_t t, int c) const { return img_.pixels[t * size_t(img_.channels) + size_t(c)]; }
    /// RGB of texel t (one channel: grey replicated; two: grey + alpha; four: alpha ignored).
    vec3 texelRGB(size_t t) const;
    /// Filtered RGB and grey (mean of RGB, or the single channel) at uv.
    vec3 lookupRGB(const vec2& uv, Filter f, Wrap w) const;
    float lookupGrey(const vec2& uv, Filter f, Wrap w) const;
    /// Gradient (∂g/∂u, ∂g/∂v) of lookupGrey's g at uv: for bilinear filtering the derivative of
    /// the bilinear interpolant inside the texel cell uv falls in (Mitsuba 3, bitmap.cpp
    /// eval_1_grad: ∂/∂x = (1−ty)(g10−g00) + ty(g11−g01), ∂/∂y = (1−tx)(g01−g00) + tx(g11−g10),
    /// times the resolution); 0 for nearest-neighbour lookups (piecewise constant).
    vec2 gradientGrey(const vec2& uv, Filter f, Wrap w) const;

    static Filter parseFilter(const std::string& s, const SourceLocation& loc);
    static Wrap parseWrap(const std::string& s, const SourceLocation& loc);

private:
    /// The bilinear cell of uv: wrapped texel columns xs, rows ys and the weights tx, ty of the
    /// second ones.
    struct Cell {
        int xs[2], ys[2];
        float tx, ty;
    };
    Cell bilinearCell(const vec2& uv, Wrap w) const;
    /// uv made finite and reduced to a few periods (no int overflow in the texel indices).
    static vec2 sanitise(const vec2& uv, Wrap w);
    /// lookupGrey's grey value of texel t.
    float texelGrey(size_t t) const;
    int wrap(int i, int n, Wrap w) const;
    Image img_;
};

}  // namespace iris
