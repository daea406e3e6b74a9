#include "spectral/ior.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "core/error.h"

namespace iris {

IOR IOR::constant(float eta) {
    IOR r;
    r.c_ = eta;
    return r;
}

IOR IOR::perChannel(const vec3& eta, const vec3& lambdas) {
    if (eta.x == eta.y && eta.y == eta.z) return constant(eta.x);  // the same value at every λ, exactly
    IOR r;
    r.kind_ = Kind::PerChannel;
    r.a_ = eta;
    r.b_ = lambdas;
    r.lerp_ = ChannelLerp(eta, lambdas);
    return r;
}

IOR IOR::tabulated(SpectrumPtr spectrum) {
    if (!spectrum) fail("IOR::tabulated: null spectrum");
    IOR r;
    r.kind_ = Kind::Tabulated;
    r.spectrum_ = std::move(spectrum);
    return r;
}

IOR IOR::cauchy(float a, float bUm2) {
    IOR r;
    r.kind_ = Kind::Cauchy;
    r.a_ = vec3(a, bUm2, 0);
    return r;
}

IOR IOR::sellmeier(const vec3& b, const vec3& cUm2) {
    IOR r;
    r.kind_ = Kind::Sellmeier;
    r.a_ = b;
    r.b_ = cUm2;
    return r;
}

SampledSpectrum IOR::sample(const SampledWavelengths& wl) const {
    if (kind_ == Kind::Constant) return SampledSpectrum(wl.size(), c_);  // = eval at every λ, without the switch
    if (kind_ == Kind::Tabulated) return spectrum_->sample(wl);
    SampledSpectrum s(wl.size());
    for (int i = 0; i < wl.size(); ++i) s[i] = at(wl, i);
    return s;
}

bool IOR::isDispersive() const {
    switch (kind_) {
        case Kind::Constant: return false;
        case Kind::Cauchy: return a_.y != 0.0f;
        case Kind::PerChannel:  // three equal values are a Constant
        case Kind::Tabulated:
        case Kind::Sellmeier: return true;
    }
    return false;
}

IOR::Range IOR::range() const {
    Range r{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    forEachValue([&](float, float v) {
        r.min = std::min(r.min, v);
        r.max = std::max(r.max, v);
    });
    if (kind_ == Kind::Tabulated) r.max = std::max(r.max, spectrum_->maxValue());  // bounds it between samples too
    return r;
}

float relativeIOR(const IOR& intIOR, const IOR& extIOR, SampledWavelengths& wl, SampledSpectrum* eta) {
    *eta = intIOR.sample(wl) / extIOR.sample(wl);
    const bool varies = [&] {
        for (int i = 1; i < eta->size(); ++i)
            if ((*eta)[i] != (*eta)[0]) return true;
        return false;
    }();
    if (wl.isRGB()) return (*eta)[1];
    if (varies) wl.terminateSecondary();
    return (*eta)[0];
}

}  // namespace iris
