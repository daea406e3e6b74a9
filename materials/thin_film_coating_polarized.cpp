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
        if (airySingleFilmPolarizationAt(angle, airyFilm(k), airySubstrate(k, below), p)) return clampedPolarization(p);
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
        return clampedPolarization(singleFilmPolarization(mode_, bounces_, lambda_[k], cosTheta, incident, rows[0], substrate));
    return clampedPolarization(stackPolarization(lambda_[k], cosTheta, incident, std::span<const Layer>(rows, size_t(stride)), substrate));
}

void ThinFilmCoating::polarizationAll(double cosTheta, bool below, PolarizationLanes& out) const {
    requireSpectral(rgb_ || belcourBarla_);
    uint32_t perEntry = n_ >= 32 ? ~0u : (1u << n_) - 1;  // entries the kernel does not give
    if (airy_)  // the kernel writes the clamped terms straight into `out` (AiryBatchOutput)
        perEntry = airyBatch(cosTheta, below, AiryBatchOutput{out.Rs, out.Rp, out.Ts, out.Tp, out.crossRRe, out.crossRIm,
                                                              out.crossTRe, out.crossTIm});
    while (perEntry) {  // other stacks, and the entries the closed form declines (as polarization())
        const int k = __builtin_ctz(perEntry);
        perEntry &= perEntry - 1;
        const FilmPolarization p = polarization(k, cosTheta, below);
        out.Rs[k] = p.power.Rs, out.Rp[k] = p.power.Rp, out.Ts[k] = p.power.Ts, out.Tp[k] = p.power.Tp;
        out.crossRRe[k] = p.crossR.real(), out.crossRIm[k] = p.crossR.imag();
        out.crossTRe[k] = p.crossT.real(), out.crossTIm[k] = p.crossT.imag();
    }
}

void ThinFilmCoating::polarizationPowersAll(double cosTheta, bool below, PolarizationLanes& out) const {
    requireSpectral(rgb_ || belcourBarla_);
    if (!airy_) {
        for (int k = 0; k < n_; ++k) {
            const ThinFilmStackResult p = polarizationPowers(k, cosTheta, below);
            out.Rs[k] = p.Rs, out.Rp[k] = p.Rp, out.Ts[k] = p.Ts, out.Tp[k] = p.Tp;
        }
        return;
    }
    exactPowersAll(cosTheta, below, out.Rs, out.Rp, out.Ts, out.Tp);
    for (int k = 0; k < n_; ++k) {  // clampedPowers: R, T ∈ [0, 1] already; T ≤ 1 − R remains
        out.Ts[k] = std::min(out.Ts[k], 1.0 - out.Rs[k]);
        out.Tp[k] = std::min(out.Tp[k], 1.0 - out.Rp[k]);
    }
}

}  // namespace iris
