// The `constvolume` volume (Mitsuba 3 src/volumes/const.cpp): `value` (float, <rgb> or
// <spectrum>; default 1) everywhere, and `to_world`, which places its box (the unit cube, as for
// every Mitsuba 3 volume: a heterogeneous medium whose sigma_t is constant fills that box only).
// Its raw channels (what phase functions read, Volume::evalChannels) are the number given (one
// channel) or the <rgb> triple (three); a <spectrum> has none.
#include <algorithm>
#include <vector>

#include "media/volumes/volume.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class ConstVolume final : public Volume {
public:
    ConstVolume(SpectrumPtr value, const mat4& toWorld, std::vector<float> raw = {})
        : Volume(toWorld), value_(std::move(value)), raw_(std::move(raw)) {
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
    int channels() const override { return int(raw_.size()); }
    void evalChannels(const vec3&, float* out) const override { std::copy(raw_.begin(), raw_.end(), out); }

private:
    SpectrumPtr value_;
    std::vector<float> raw_;
    ValueRange range_;
};

/// The number or <rgb> written as `value` (default 1), or nothing for a spectrum.
std::vector<float> rawValue(const Properties& p) {
    const Properties::Entry* e = p.present("value") ? &p.require("value") : nullptr;
    if (!e) return {1.0f};
    if (const float* f = std::get_if<float>(&e->value)) return {*f};
    if (const int64_t* i = std::get_if<int64_t>(&e->value)) return {float(*i)};
    if (const RGBValue* c = std::get_if<RGBValue>(&e->value)) return {c->rgb.x, c->rgb.y, c->rgb.z};
    return {};
}

std::shared_ptr<Volume> create(const Properties& p, SpectrumKind kind) {
    std::vector<float> raw = rawValue(p);
    return std::make_shared<ConstVolume>(getSpectrum(p, "value", kind, 1.0f), readToWorld(p), std::move(raw));
}

}  // namespace

VolumePtr makeConstVolume(SpectrumPtr value, const mat4& toWorld) {
    return std::make_shared<ConstVolume>(std::move(value), toWorld);
}

IRIS_REGISTER(VolumeRegistry, "constvolume", create);

}  // namespace iris
