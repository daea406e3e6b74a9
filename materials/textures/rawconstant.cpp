// The `rawconstant` texture (Mitsuba 3, added with its normal/bump-map fixes of v3.7 for the
// "identity" normal map of mitsuba-data's test_normalmap_identity_roughconductor): a constant
// whose value is returned as written, never spectrally upsampled or colour-converted — unlike a
// plain <rgb>, whose value becomes a smooth spectrum in spectral mode.
//
// Parameter `value` (required): a <float> or a three-valued <vector>, <point> or <rgb>.
//   * float texture: the float, or the mean of the three values;
//   * spectrum texture, RGB mode (RGB-mode wavelengths, as normalmap reads its map): the three
//     values as they are (a float is replicated); spectral mode: the float at every wavelength, or
//     the mean of the three values (a raw triple is no spectrum; iris does not throw mid-render as
//     Mitsuba does when a raw RGB texture is asked for a spectrum).
#include <variant>

#include "core/registry.h"
#include "materials/textures/texture.h"

namespace iris {
namespace {

/// The value as three components (a float replicated) and whether it was a float.
struct RawValue {
    vec3 v{0.0f};
    bool scalar = false;

    explicit RawValue(const Properties& p) {
        const Properties::Entry& e = p.require("value");
        if (const float* f = std::get_if<float>(&e.value)) {
            v = vec3(*f);
            scalar = true;
        } else if (const int64_t* i = std::get_if<int64_t>(&e.value)) {
            v = vec3(float(*i));
            scalar = true;
        } else if (const VectorValue* vv = std::get_if<VectorValue>(&e.value)) {
            v = vv->v;
        } else if (const PointValue* pv = std::get_if<PointValue>(&e.value)) {
            v = pv->v;
        } else if (const RGBValue* rgb = std::get_if<RGBValue>(&e.value)) {
            v = rgb->rgb;
        } else {
            failAt(e.loc, "rawconstant: 'value' must be a <float>, <vector>, <point> or <rgb>");
        }
        if (!isFinite(v)) failAt(e.loc, "rawconstant: 'value' must be finite");
    }
    float mean() const { return scalar ? v.x : (v.x + v.y + v.z) / 3.0f; }
};

class RawConstantSpectrum final : public SpectrumTexture {
public:
    explicit RawConstantSpectrum(const Properties& p) : value_(p) {}
    SampledSpectrum eval(const TextureQuery&, const SampledWavelengths& wl) const override {
        if (wl.isRGB()) {
            SampledSpectrum s(wl.size());
            for (int i = 0; i < wl.size(); ++i) s[i] = value_.v[std::min(i, 2)];
            return s;
        }
        return SampledSpectrum(wl.size(), value_.mean());
    }
    bool isConstant() const override { return true; }

private:
    RawValue value_;
};

class RawConstantFloat final : public FloatTexture {
public:
    explicit RawConstantFloat(const Properties& p) : value_(RawValue(p).mean()) {}
    float eval(const TextureQuery&) const override { return value_; }
    vec2 gradient(const TextureQuery&, float) const override { return vec2(0.0f); }
    bool isConstant() const override { return true; }

private:
    float value_;
};

std::shared_ptr<SpectrumTexture> createSpectrum(const Properties& p, SpectrumKind) {
    return std::make_shared<RawConstantSpectrum>(p);
}
std::shared_ptr<FloatTexture> createFloat(const Properties& p) { return std::make_shared<RawConstantFloat>(p); }

}  // namespace

IRIS_REGISTER(SpectrumTextureRegistry, "rawconstant", createSpectrum);
IRIS_REGISTER(FloatTextureRegistry, "rawconstant", createFloat);

}  // namespace iris
