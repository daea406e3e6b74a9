#include "spectral/thin_film_polarization.h"

#include <algorithm>
#include <cmath>

#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_stack_detail.h"

namespace iris {

using namespace thin_film_detail;

namespace {

/// √(P_s P_p) times the phase of a_s a_p* (0 when either amplitude vanishes): a coherent cross
/// term whose magnitude matches the (clamped) powers.
complexd coherentCross(double Ps, double Pp, complexd as, complexd ap) {
    const complexd z = as * std::conj(ap);
    const double m = std::abs(z);
    if (!(m > 0) || !std::isfinite(m)) return 0.0;
    return std::sqrt(std::max(0.0, Ps * Pp)) * (z / m);
}

/// z/|z| in real arithmetic, 0 when |z| underflows to 0 (z is finite here).
complexd unitPhase(complexd z) {
    const double m = std::sqrt(airy_detail::cnorm(z));
    return m > 0 ? complexd(z.real() / m, z.imag() / m) : complexd(0.0, 0.0);
}

/// s and p interface data of one film (docs/thin_film.md §2).
struct FilmPair {
    FilmInterfaces s, p;
};
FilmPair filmPair(double lambdaNm, double cosThetaIncident, double incidentIor, const Layer& film, complexd substrateIor) {
    return {filmInterfaces(Pol::S, lambdaNm, cosThetaIncident, incidentIor, film, substrateIor),
            filmInterfaces(Pol::P, lambdaNm, cosThetaIncident, incidentIor, film, substrateIor)};
}

/// T of one polarisation from its (scaled) transmitted amplitude sum, as thin_film_stack.cpp's
/// transmittance: y0 Re(y2) |tScaled e^{iδ} Σ|².
double filmT(const FilmInterfaces& f, complexd sum) { return f.y0 * f.y2.real() * std::norm(f.tScaled * f.halfPhase * sum); }

/// Truncated coherent sums (thin_film_stack.cpp truncatedSingleFilm) with their amplitudes.
FilmPolarization truncated(const FilmPair& f, int K) {
    complexd r[2], t[2];
    double R[2], T[2];
    const FilmInterfaces* pol[2] = {&f.s, &f.p};
    for (int k = 0; k < 2; ++k) {
        const FilmInterfaces& g = *pol[k];
        // r_K = r01 + (1 − r01²) r12 E Σ_{m<K} (−r01 r12 E)^m, t_K ∝ t01 t12 e^{iδ} Σ (Heavens ch. 4).
        const complexd ratio = -g.r01 * g.r12 * g.E;
        complexd sum = 0.0, term = 1.0;
        for (int m = 0; m < K; ++m) sum += term, term *= ratio;
        r[k] = g.r01 + (1.0 - g.r01 * g.r01) * g.r12 * g.E * sum;
        t[k] = g.tScaled * g.halfPhase * sum;
        R[k] = std::clamp(std::norm(r[k]), 0.0, 1.0);
        T[k] = std::clamp(filmT(g, sum), 0.0, 1.0 - R[k]);
    }
    FilmPolarization out;
    out.power = {R[0], R[1], T[0], T[1]};
    out.crossR = coherentCross(R[0], R[1], r[0], r[1]);
    out.crossT = coherentCross(T[0], T[1], t[0], t[1]);
    return out;
}

/// Incoherent sums: the Mueller matrices of the beams add (Heavens ch. 4 for the powers). Beam 0
/// reflects at the top; beam j ≥ 1 crosses the film 2j times: its s·p* product is
/// T01s T01p (r12s r12p*)(ρ)^{j−1} a² per further round trip, ρ = (r10s r10p*)(r12s r12p*) a²,
/// r10 = −r01, a = |e^{iδ}|² (the propagation phase is common to s and p and cancels).
FilmPolarization incoherent(const FilmPair& f) {
    const FilmInterfaces &s = f.s, &p = f.p;
    const double a = std::norm(s.halfPhase), a2 = a * a;  // single pass a = e^{−2 Im δ}, round trip a²
    const double R01[2] = {std::min(1.0, std::norm(s.r01)), std::min(1.0, std::norm(p.r01))};
    const double R12[2] = {std::min(1.0, std::norm(s.r12)), std::min(1.0, std::norm(p.r12))};
    double R[2], T[2];
    for (int k = 0; k < 2; ++k) {  // the powers exactly as incoherentSingleFilm sums them
        const double den = 1.0 - R01[k] * R12[k] * a * a;
        const double T01 = 1.0 - R01[k], T12 = 1.0 - R12[k];
        R[k] = den > 0 ? std::min(1.0, R01[k] + T01 * T01 * R12[k] * a * a / den) : 1.0;
        T[k] = den > 0 ? std::clamp(T01 * T12 * a / den, 0.0, 1.0 - R[k]) : 0.0;
    }
    FilmPolarization out;
    out.power = {R[0], R[1], T[0], T[1]};
    const complexd top = s.r01 * std::conj(p.r01), bottom = s.r12 * std::conj(p.r12);
    const complexd den = 1.0 - top * bottom * a2;  // 1 − ρ
    if (!(std::abs(den) > 0)) return out;
    const double T01s = 1.0 - R01[0], T01p = 1.0 - R01[1];
    out.crossR = top + T01s * T01p * bottom * a2 / den;
    out.crossT = std::sqrt(T01s * (1.0 - R12[0]) * T01p * (1.0 - R12[1])) * a / den;
    return out;
}

}  // namespace

StackAmplitudes thinFilmStackAmplitudes(double lambdaNm, double cosThetaIncident, double incidentIor,
                                        std::span<const Layer> layers, complexd substrateIor) {
    const double c = std::clamp(cosThetaIncident, 0.0, 1.0);
    const double s = incidentIor * std::sqrt(std::max(0.0, 1.0 - c * c));
    const double q0 = incidentIor * c;
    const double y0[2] = {q0, q0 / (incidentIor * incidentIor)};
    AmpRT amp[2];
    transferMatrix(lambdaNm, y0, s, layers, substrateIor, amp);
    StackAmplitudes a{amp[0].r, amp[1].r, amp[0].t, amp[1].t, {}};
    // The powers as thinFilmStackRT gives them (same transfer matrix, same clamps).
    a.power = {std::min(1.0, std::norm(amp[0].r)), std::min(1.0, std::norm(amp[1].r)), std::clamp(amp[0].T, 0.0, 1.0),
               std::clamp(amp[1].T, 0.0, 1.0)};
    return a;
}

ThinFilmStackResult clampedPowers(ThinFilmStackResult r) {
    r.Rs = std::clamp(r.Rs, 0.0, 1.0);
    r.Rp = std::clamp(r.Rp, 0.0, 1.0);
    r.Ts = std::clamp(r.Ts, 0.0, 1.0 - r.Rs);
    r.Tp = std::clamp(r.Tp, 0.0, 1.0 - r.Rp);
    return r;
}

FilmPolarization clampedPolarization(FilmPolarization p) {
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

bool airySingleFilmPolarizationAt(const AiryAngle& angle, const AiryFilmConstants& film, const SquaredIndex& substrate,
                                  FilmPolarization& out) {
    using airy_detail::cmul;
    AiryFilmTerms t;
    if (!airySingleFilmTerms(angle, film, substrate, t)) return false;
    complexd r[2], phaseT[2];
    for (int k = 0; k < 2; ++k) {
        // r = num/den = num·conj(den)/|den|²; the phase of t ∝ y1/den is that of y1·conj(den).
        const complexd z = cmul(t.num[k], std::conj(t.den[k]));
        r[k] = complexd(z.real() / t.dd[k], z.imag() / t.dd[k]);
        phaseT[k] = unitPhase(cmul(t.y1[k], std::conj(t.den[k])));  // 0 only where t ≈ 0 (T ≈ 0)
    }
    out.power = t.clampedPowers();
    out.crossR = cmul(r[0], std::conj(r[1]));  // r_s r_p* (the interface layout's C + iD)
    // coherentCross: √(T_s T_p) · (t_s t_p*)/|t_s t_p*|.
    out.crossT = std::sqrt(std::max(0.0, out.power.Ts * out.power.Tp)) * cmul(phaseT[0], std::conj(phaseT[1]));
    return true;
}

FilmPolarization stackPolarization(double lambdaNm, double cosThetaIncident, double incidentIor, std::span<const Layer> layers,
                                   complexd substrateIor) {
    const StackAmplitudes a = thinFilmStackAmplitudes(lambdaNm, cosThetaIncident, incidentIor, layers, substrateIor);
    FilmPolarization out;
    out.power = a.power;
    out.crossR = a.rs * std::conj(a.rp);
    out.crossT = coherentCross(a.power.Ts, a.power.Tp, a.ts, a.tp);
    return out;
}

FilmPolarization singleFilmPolarization(ThinFilmPhaseMode mode, int K, double lambdaNm, double cosThetaIncident,
                                        double incidentIor, const Layer& film, complexd substrateIor) {
    switch (mode) {
        case ThinFilmPhaseMode::Exact: {
            FilmPolarization p;
            if (airySingleFilmPolarizationAt(airyAngle(cosThetaIncident, incidentIor), airyFilmConstants(lambdaNm, film),
                                             squaredIndex(substrateIor), p))
                return p;
            return stackPolarization(lambdaNm, cosThetaIncident, incidentIor, std::span<const Layer>(&film, 1), substrateIor);
        }
        case ThinFilmPhaseMode::Truncated:
            return truncated(filmPair(lambdaNm, cosThetaIncident, incidentIor, film, substrateIor), std::max(K, 0));
        case ThinFilmPhaseMode::Incoherent:
            return incoherent(filmPair(lambdaNm, cosThetaIncident, incidentIor, film, substrateIor));
    }
    return {};
}

}  // namespace iris
