// The `constvolume` volume (Mitsuba 3 src/volumes/const.cpp): `value` (float, <rgb> or
// <spectrum>; default 1) everywhere, and `to_world`, which places its box (the unit cube, as for
// every Mitsuba 3 volume: a heterogeneous medium whose sigma_t is constant fills that box only).
#include <algorithm>

#include "materials/volumes/volume.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class ConstVolume final : public Volume {
public:
    ConstVolume(SpectrumPtr value, const mat4& toWorld) : Volume(toWorld), value_(std::move(value)) {
        const vec3 rgb = value_->rgbValue();  // the RGB-mode value of Reflectance/Illuminant kinds
        range_.min = std::min({rgb.x, rgb.y, rgb.z});
        range_.max = std::max({rgb.x, rgb.y, rgb.z, value_->maxValue()});
        for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 1.0f) {  // 1 nm steps
            const float v = value_->eval(lambda);
            range_.min = std::min(range_.min, v);
            range_.max = std::max(range_.max, v);
        }
    }

    SampledSpectrum eval(const vec3&, const SampledWavelengths& wl) const override { return value_->sample(wl); }
    /// Spectrum::maxValue bounds every wavelength; RGB mode returns rgbValue (or, for Unbounded
    /// spectra, values at the channel wavelengths), which range_.max also covers.
    float maxValue() const override { return range_.max; }
    ValueRange range() const override { return range_; }
    bool isConstant() const override { return true; }

private:
    SpectrumPtr value_;
    ValueRange range_;
};

std::shared_ptr<Volume> create(const Properties& p, SpectrumKind kind) {
    return std::make_shared<ConstVolume>(getSpectrum(p, "value", kind, 1.0f), readToWorld(p));
}

}  // namespace

VolumePtr makeConstVolume(SpectrumPtr value, const mat4& toWorld) {
    return std::make_shared<ConstVolume>(std::move(value), toWorld);
}

IRIS_REGISTER(VolumeRegistry, "constvolume", create);

}  // namespace iris
