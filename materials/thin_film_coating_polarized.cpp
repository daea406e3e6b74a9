// ThinFilmCoating::polarization: the stack's s and p terms for the polarized mode
// (docs/polarization.md), from the same layers, media and phase mode as stackRT and
// stackRTFromBelow (materials/thin_film_coating.cpp), through spectral/thin_film_polarization.h.
#include "materials/thin_film_coating.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "spectral/thin_film_airy.h"

namespace iris {

namespace {

/// The powers clamped as the coating clamps them (R ∈ [0, 1], T ∈ [0, 1 − R]).
ThinFilmStackResult clampedPowers(ThinFilmStackResult r) {
    r.Rs = std::clamp(r.Rs, 0.0, 1.0);
    r.Rp = std::clamp(r.Rp, 0.0, 1.0);
    r.Ts = std::clamp(r.Ts, 0.0, 1.0 - r.Rs);
    r.Tp = std::clamp(r.Tp, 0.0, 1.0 - r.Rp);
    return r;
}

/// clampedPowers, and the cross terms kept within √(P_s P_p) (their magnitude for a coherent sum).
FilmPolarization clamped(FilmPolarization p) {
    p.power = clampedPowers(p.power);
    const ThinFilmStackResult& r = p.power;
    auto bound = [](complexd c, double limit) {
        const double m = std::sqrt(std::norm(c));  // |c| without hypot's overflow guard: |c| ≤ ~1 here
        return m > limit && m > 0 ? c * (limit / m) : c;
    };
    p.crossR = bound(p.crossR, std::sqrt(r.Rs * r.Rp));
    p.crossT = bound(p.crossT, std::sqrt(r.Ts * r.Tp));
    return p;
}

void requireSpectral(bool rgb) {
    if (rgb) fail("the polarized mode is spectral: a thin film in RGB mode has no polarization terms");
}

}  // namespace

ThinFilmStackResult ThinFilmCoating::polarizationPowers(int k, double cosTheta, bool below) const {
    requireSpectral(rgb_ || belcourBarla_);
    return clampedPowers(below ? stackRTFromBelow(k, cosTheta) : stackRT(k, cosTheta));
}

FilmPolarization ThinFilmCoating::polarization(int k, double cosTheta, bool below) const {
    requireSpectral(rgb_ || belcourBarla_);
    if (airy_) {  // exact single film: the closed form from the hoisted constants, as exactAt
        const AiryAngle angle = airyAngle(cosTheta, below ? substrate_[k].real() : extIor_);
        FilmPolarization p;
        if (airySingleFilmPolarizationAt(angle, airyFilm(k), airySubstrate(k, below), p)) return clamped(p);
    }
    const int stride = 1 + nExtra_;
    Layer rows[9];
    for (int j = 0; j < stride; ++j) {
        const int from = below ? stride - 1 - j : j;  // lit from the substrate: the reversed stack
        rows[j] = layers_ ? layers_[k * stride + from] : Layer{film_[k], thickness_};
    }
    const double incident = below ? substrate_[k].real() : extIor_;
    const complexd substrate = below ? complexd(extIor_, 0.0) : substrate_[k];
    if (nExtra_ == 0)
        return clamped(singleFilmPolarization(mode_, bounces_, lambda_[k], cosTheta, incident, rows[0], substrate));
    return clamped(stackPolarization(lambda_[k], cosTheta, incident, std::span<const Layer>(rows, size_t(stride)), substrate));
}

void ThinFilmCoating::polarizationAll(double cosTheta, bool below, FilmPolarization* out) const {
    requireSpectral(rgb_ || belcourBarla_);
    if (!airy_) {
        for (int k = 0; k < n_; ++k) out[k] = polarization(k, cosTheta, below);
        return;
    }
    alignas(32) double Rs[kMaxWavelengths], Rp[kMaxWavelengths], Ts[kMaxWavelengths], Tp[kMaxWavelengths];
    alignas(32) double cRRe[kMaxWavelengths], cRIm[kMaxWavelengths], cTRe[kMaxWavelengths], cTIm[kMaxWavelengths];
    const uint32_t declined = airyBatch(cosTheta, below, AiryBatchOutput{Rs, Rp, Ts, Tp, cRRe, cRIm, cTRe, cTIm});
    for (int k = 0; k < n_; ++k) {
        if (declined >> k & 1) {  // the transfer matrix, as polarization() falls back
            out[k] = polarization(k, cosTheta, below);
            continue;
        }
        FilmPolarization p;
        p.power = {Rs[k], Rp[k], Ts[k], Tp[k]};
        p.crossR = complexd(cRRe[k], cRIm[k]);
        p.crossT = complexd(cTRe[k], cTIm[k]);
        out[k] = clamped(p);
    }
}

void ThinFilmCoating::polarizationPowersAll(double cosTheta, bool below, ThinFilmStackResult* powers) const {
    requireSpectral(rgb_ || belcourBarla_);
    if (!airy_) {
        for (int k = 0; k < n_; ++k) powers[k] = polarizationPowers(k, cosTheta, below);
        return;
    }
    alignas(32) double Rs[kMaxWavelengths], Rp[kMaxWavelengths], Ts[kMaxWavelengths], Tp[kMaxWavelengths];
    const uint32_t declined = airyBatch(cosTheta, below, AiryBatchOutput{Rs, Rp, Ts, Tp});
    for (int k = 0; k < n_; ++k)
        powers[k] = declined >> k & 1 ? polarizationPowers(k, cosTheta, below) : clampedPowers({Rs[k], Rp[k], Ts[k], Tp[k]});
}

}  // namespace iris
