#include "materials/fresnel_polarized.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace iris {
namespace {

using complexd = std::complex<double>;

/// q = sqrt(ñ² − sin²θi) with Im q ≥ 0 (the decaying wave for e^{−iωt}; docs/thin_film.md §1).
complexd decayingRoot(complexd radicand) {
    complexd q = std::sqrt(radicand);
    if (q.imag() < 0 || (q.imag() == 0 && q.real() < 0)) q = -q;
    return q;
}

InterfaceMuellerTerms termsOf(complexd rs, complexd rp, double scale) {
    const double Rs = std::norm(rs) * scale, Rp = std::norm(rp) * scale;
    const complexd c = rs * std::conj(rp) * scale;  // C + iD = r_s r_p* (file comment)
    return {float(0.5 * (Rs + Rp)), float(0.5 * (Rs - Rp)), float(c.real()), float(c.imag())};
}

}  // namespace

InterfaceMuellerTerms reflectionTerms(float cosThetaI, float eta, float k) {
    const bool outside = cosThetaI >= 0;
    complexd n(eta, k);
    if (!outside) n = 1.0 / n;
    if ((k == 0 && eta == 1.0f) || std::norm(n) == 0) return {};  // Mitsuba: index-matched or invalid
    const double ci = std::min(1.0, std::abs(double(cosThetaI)));
    const complexd n2 = n * n;
    const complexd q = decayingRoot(n2 - (1.0 - ci * ci));
    // Born & Wolf §1.5.2 with the incident index 1 (relative indices).
    const complexd rs = (ci - q) / (ci + q), rp = (n2 * ci - q) / (n2 * ci + q);
    return termsOf(rs, rp, 1.0);
}

InterfaceMuellerTerms transmissionTerms(float cosThetaI, float eta) {
    const bool outside = cosThetaI >= 0;
    const double n = outside ? eta : 1.0 / eta;  // η_t / η_i
    const double ci = std::min(1.0, std::abs(double(cosThetaI)));
    if (n == 1.0) return {1, 0, 1, 0};           // index-matched: straight through, unchanged
    const double ct2 = 1.0 - (1.0 - ci * ci) / (n * n);
    if (!(ct2 > 0) || !(ci > 1e-8)) return {};  // total internal reflection or grazing
    const double ct = std::sqrt(ct2);
    const double ts = 2.0 * ci / (ci + n * ct), tp = 2.0 * ci / (n * ci + ct);
    // Power factor η_t cos θt / (η_i cos θi) (Born & Wolf §1.5.3, eq. 1.5.39).
    return termsOf(ts, tp, n * ct / ci);
}

SlabMuellerTerms slabTerms(float cosThetaI, float eta) {
    const double ci = std::min(1.0, std::abs(double(cosThetaI))), n = eta;
    if (n == 1.0) return {{}, {1, 0, 1, 0}};
    const double ct = std::sqrt(std::max(0.0, 1.0 - (1.0 - ci * ci) / (n * n)));
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);  // Born & Wolf §1.5.2
    const double Rs = rs * rs, Rp = rp * rp, Ts = 1.0 - Rs, Tp = 1.0 - Rp;
    const double RsS = 2.0 * Rs / (1.0 + Rs), RpS = 2.0 * Rp / (1.0 + Rp);
    const double TsS = Ts / (1.0 + Rs), TpS = Tp / (1.0 + Rp);
    const double den = 1.0 - Rs * Rp;
    const double cross = den > 0 ? Ts * Tp / den : 0.0;  // grazing: R = 1, nothing enters
    SlabMuellerTerms t;
    t.reflection = {float(0.5 * (RsS + RpS)), float(0.5 * (RsS - RpS)), float(rs * rp * (1.0 + cross)), 0.0f};
    t.transmission = {float(0.5 * (TsS + TpS)), float(0.5 * (TsS - TpS)), float(cross), 0.0f};
    return t;
}

}  // namespace iris
