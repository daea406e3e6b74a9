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
    /// Errors name the file. Files already loaded (and still in use) with the same `raw` are shared.
    static std::shared_ptr<const Bitmap> load(const std::string& path, bool raw);
    /// The same without the cache (always reads the file).
    static std::shared_ptr<const Bitmap> loadUncached(const std::string& path, bool raw);

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

    static Filter parseFilter(const std::string& s, const SourceLocation& loc);
    static Wrap parseWrap(const std::string& s, const SourceLocation& loc);

private:
    int wrap(int i, int n, Wrap w) const;
    Image img_;
};

}  // namespace iris
