// Thin-film stack optics: interface coefficients, Airy sums and the transfer-matrix method.
// Derivations and the numerics choices for ill-conditioned cases are in docs/thin_film.md.
#include "spectral/thin_film_stack.h"

#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_stack_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iris {

using namespace thin_film_detail;

namespace thin_film_detail {


/// e^{z} − 1 without cancellation for small |z| (expm1 of the real part, −2 sin²(y/2) for cos y − 1).
complexd expm1c(complexd z) {
    const double x = z.real(), y = z.imag();
    const double ex = std::exp(x);
    const double sh = std::sin(0.5 * y);
    return {std::expm1(x) * std::cos(y) - 2.0 * sh * sh, ex * std::sin(y)};
}

/// (e^{2iδ} − 1)/(2q) with δ = k0 q d: finite as q → 0 (limit i k0 d), computed without dividing
/// a cancelled difference by a tiny q.
complexd halfExpm1OverQ(complexd q, double k0d) {
    const complexd z = complexd(0.0, 2.0 * k0d) * q;  // 2iδ
    if (std::abs(z) < 1e-6) return complexd(0.0, k0d) * (1.0 + 0.5 * z + z * z / 6.0);  // series of (e^z−1)/z
    return expm1c(z) / (2.0 * q);
}


/// Both polarisations of the transfer-matrix method in one pass over the layers: q, E = e^{2iδ}
/// and g = (E − 1)/(2q) of each layer (the csqrt, cexp and expm1 work) are computed once and used
/// by s and p; each polarisation keeps its own (B, C) and scale, with the same operations as a
/// separate pass. y0[0], y0[1]: incident admittances for s and p. Returns {s, p}.
void transferMatrix(double lambdaNm, const double y0[2], double s, std::span<const Layer> layers, complexd substrateIor,
                    AmpRT out[2]) {
    // Characteristic matrix of layer j for the e^{−iωt} convention (Born & Wolf §1.6.2; Macleod's
    // ch. 2 form is the same with i → −i for his e^{+iωt}, ñ = n − ik), multiplied by e^{iδ}:
    //   e^{iδ} [[cos δ, −i sin δ / y], [−i y sin δ, cos δ]]
    //     = [[(1+E)/2, (1−E)/(2y)], [y(1−E)/2, (1+E)/2]],   E = e^{2iδ}, |E| ≤ 1 since Im δ ≥ 0.
    // (1−E)/(2y) and y(1−E)/2 are written through g = (E−1)/(2q): s: −g, −q²g; p: −ñ²g, −q²g/ñ².
    // [B; C] = Π_j M_j [1; y_sub]; r = (y0 B − C)/(y0 B + C); T = 4 y0 Re(y_sub)/|y0 B + C|² (Macleod
    // ch. 2), times |Π e^{iδ_j}|² for the scaling, which is tracked as a logarithm.
    const double k0 = kTwoPi / lambdaNm;
    const complexd qSub = normalWaveNumber(substrateIor, s);
    const complexd ySub[2] = {admittance(Pol::S, qSub, substrateIor), admittance(Pol::P, qSub, substrateIor)};
    complexd B[2] = {1.0, 1.0}, C[2] = {ySub[0], ySub[1]};
    double logScale[2] = {0.0, 0.0};  // (B, C)_true = (B, C) · e^{logScale} · e^{−iΦ}
    double phase = 0.0;                // Φ = Σ_j Re δ_j, the phase the scaling by e^{iδ_j} removed
    for (auto it = layers.rbegin(); it != layers.rend(); ++it) {
        const complexd n = it->ior;
        const complexd q = normalWaveNumber(n, s);
        const double k0d = k0 * it->thicknessNm;
        const complexd delta = k0d * q;
        const complexd E = std::exp(complexd(0.0, 2.0) * delta);  // |E| = e^{−2 Im δ} ≤ 1
        const complexd g = halfExpm1OverQ(q, k0d);
        phase += delta.real();
        const complexd n2 = n * n;
        const complexd m00 = 0.5 * (1.0 + E);
        const complexd qqg = q * q * g;
        const complexd m01[2] = {-g, -(n2 * g)};
        const complexd m10[2] = {-qqg, -(qqg / n2)};
        for (int k = 0; k < 2; ++k) {
            const complexd nb = m00 * B[k] + m01[k] * C[k];
            const complexd nc = m10[k] * B[k] + m00 * C[k];
            B[k] = nb;
            C[k] = nc;
            logScale[k] += delta.imag();  // true matrix = e^{−iδ}·scaled one, |e^{−iδ}| = e^{Im δ}
            // Renormalise to keep (B, C) of order one.
            const double m = std::max(std::abs(B[k]), std::abs(C[k]));
            if (m > 0 && std::isfinite(m)) {
                B[k] /= m;
                C[k] /= m;
                logScale[k] += std::log(m);
            }
        }
    }
    for (int k = 0; k < 2; ++k) {
        // (B, C)_true = (B, C) · e^{logScale}: T = 4 y0 Re(y_sub) / (|den|² e^{2 logScale}), evaluated
        // in logarithms so that thick absorbing stacks underflow gracefully to T = 0.
        const complexd den = y0[k] * B[k] + C[k];
        const double aden = std::abs(den);
        if (!(aden > 0) || !std::isfinite(aden)) {
            out[k] = {complexd(-1.0, 0.0), 0.0, complexd(0.0, 0.0)};
            continue;
        }
        const complexd r = (y0[k] * B[k] - C[k]) / den;
        const double num = 4.0 * y0[k] * ySub[k].real();
        const double T = num > 0 ? std::exp(std::log(num) - 2.0 * std::log(aden) - 2.0 * logScale[k]) : 0.0;
        // Tangential transmission coefficient t = 2 y0 / (y0 B + C)_true (Macleod ch. 2: the
        // substrate's tangential field per unit incident one), for the polarized mode's phases.
        const complexd t = 2.0 * y0[k] / den * std::exp(complexd(-logScale[k], phase));
        out[k] = {r, T, t};
    }
}

}  // namespace thin_film_detail

complexd normalWaveNumber(complexd ior, double sinInvariant) {
    complexd q = std::sqrt(ior * ior - complexd(sinInvariant * sinInvariant, 0.0));
    // Decaying branch (e^{−iωt}: the field e^{i k0 q z} decays for Im q > 0); std::sqrt returns the
    // principal root, which can land on Im < 0 when the radicand's imaginary part is −0.
    if (q.imag() < 0 || (q.imag() == 0 && q.real() < 0)) q = -q;
    return q;
}

FresnelAmplitudes fresnelAmplitudes(double cosThetaI, double iorI, complexd iorT) {
    cosThetaI = std::clamp(cosThetaI, 0.0, 1.0);
    const double sinI = std::sqrt(std::max(0.0, 1.0 - cosThetaI * cosThetaI));
    const double s = iorI * sinI;
    const complexd qi(iorI * cosThetaI, 0.0);
    const complexd qt = normalWaveNumber(iorT, s);
    const complexd ni2(iorI * iorI, 0.0), nt2 = iorT * iorT;
    FresnelAmplitudes a;
    // Born & Wolf §1.5.2 (Fresnel formulae), with n cosθ = q.
    const complexd ds = qi + qt;
    const complexd dp = nt2 * qi + ni2 * qt;
    a.rs = (qi - qt) / ds;
    a.ts = 2.0 * qi / ds;
    a.rp = (nt2 * qi - ni2 * qt) / dp;
    a.tp = 2.0 * complexd(iorI, 0.0) * iorT * qi / dp;
    return a;
}

ThinFilmStackResult fresnelInterfaceRT(double cosThetaI, double iorI, complexd iorT) {
    return thinFilmStackRT(550.0, cosThetaI, iorI, {}, iorT);
}

ThinFilmStackResult thinFilmStackRT(double lambdaNm, double cosThetaIncident, double incidentIor,
                            std::span<const Layer> layers, complexd substrateIor) {
    const double c = std::clamp(cosThetaIncident, 0.0, 1.0);
    const double s = incidentIor * std::sqrt(std::max(0.0, 1.0 - c * c));
    const double q0 = incidentIor * c;
    ThinFilmStackResult res;
    const double y0[2] = {q0, q0 / (incidentIor * incidentIor)};
    AmpRT amp[2];
    transferMatrix(lambdaNm, y0, s, layers, substrateIor, amp);
    const AmpRT &as = amp[0], &ap = amp[1];
    res.Rs = std::min(1.0, std::norm(as.r));
    res.Rp = std::min(1.0, std::norm(ap.r));
    res.Ts = std::clamp(as.T, 0.0, 1.0);
    res.Tp = std::clamp(ap.T, 0.0, 1.0);
    return res;
}

namespace thin_film_detail {

FilmInterfaces filmInterfaces(Pol pol, double lambdaNm, double cosThetaIncident, double incidentIor,
                              const Layer& film, complexd substrateIor) {
    const double c = std::clamp(cosThetaIncident, 0.0, 1.0);
    const double s = incidentIor * std::sqrt(std::max(0.0, 1.0 - c * c));
    const complexd q0(incidentIor * c, 0.0);
    const complexd q1 = normalWaveNumber(film.ior, s);
    const complexd q2 = normalWaveNumber(substrateIor, s);
    const complexd y0 = admittance(pol, q0, complexd(incidentIor, 0.0));
    const complexd y1 = admittance(pol, q1, film.ior);
    const complexd y2 = admittance(pol, q2, substrateIor);
    auto safe = [](complexd d) { return d == complexd(0.0, 0.0) ? complexd(1e-300, 0.0) : d; };
    const complexd d01 = safe(y0 + y1), d12 = safe(y1 + y2);
    FilmInterfaces f;
    f.r01 = (y0 - y1) / d01;  // Born & Wolf §1.5.2 in admittance form
    f.r12 = (y1 - y2) / d12;
    // Tangential-field transmission t01 = 2y0/(y0+y1), t12 = 2y1/(y1+y2). T = Re(y2)/y0 |t|²; the
    // factor y0 is divided out analytically so that grazing incidence (y0 = 0) is exact.
    f.tScaled = 2.0 / d01 * (2.0 * y1 / d12);  // = t01 t12 / y0
    const complexd delta = kTwoPi / lambdaNm * film.thicknessNm * q1;
    f.E = std::exp(complexd(0.0, 2.0) * delta);
    f.halfPhase = std::exp(complexd(0.0, 1.0) * delta);
    f.y0 = y0.real();
    f.y2 = y2;
    return f;
}

}  // namespace thin_film_detail

namespace {

/// T from the (scaled) transmitted amplitude sum: T = Re(y2)/y0 |y0 · tScaled · Σ|² = y0 Re(y2)|tScaled Σ|².
double transmittance(const FilmInterfaces& f, complexd sum) {
    return std::clamp(f.y0 * f.y2.real() * std::norm(f.tScaled * f.halfPhase * sum), 0.0, 1.0);
}

ThinFilmStackResult combine(const AmpRT& s, const AmpRT& p, bool clampR) {
    ThinFilmStackResult r;
    r.Rs = clampR ? std::min(1.0, std::norm(s.r)) : std::norm(s.r);
    r.Rp = clampR ? std::min(1.0, std::norm(p.r)) : std::norm(p.r);
    r.Ts = s.T;
    r.Tp = p.T;
    return r;
}

}  // namespace

SquaredIndex squaredIndex(complexd ior) {
    const complexd sq = airy_detail::cmul(ior, ior);
    const double nn = airy_detail::cnorm(sq);
    return {sq, complexd(sq.real() / nn, -sq.imag() / nn)};  // 1/z = conj(z)/|z|²
}
AiryFilmConstants airyFilmConstants(double lambdaNm, double thicknessNm, const SquaredIndex& n1) {
    return {n1.sq, n1.inv, kTwoPi / lambdaNm * thicknessNm};  // k0 d = 2π d/λ
}
AiryFilmConstants airyFilmConstants(double lambdaNm, const Layer& film) {
    return airyFilmConstants(lambdaNm, film.thicknessNm, squaredIndex(film.ior));
}

bool airySingleFilmFast(double cosThetaIncident, double incidentIor, const AiryFilmConstants& film,
                        const SquaredIndex& substrate, ThinFilmStackResult& out) {
    return airySingleFilmFastAt(airyAngle(cosThetaIncident, incidentIor), film, substrate, out);
}

ThinFilmStackResult airySingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor, const Layer& film,
                               complexd substrateIor) {
    ThinFilmStackResult r;
    if (airySingleFilmFast(cosThetaIncident, incidentIor, airyFilmConstants(lambdaNm, film), squaredIndex(substrateIor), r))
        return r;
    // Degenerate for the closed form (q1 = 0 exactly): the transfer matrix, which is well
    // conditioned there (halfExpm1OverQ), gives the same quantity.
    return thinFilmStackRT(lambdaNm, cosThetaIncident, incidentIor, std::span<const Layer>(&film, 1), substrateIor);
}

ThinFilmStackResult airySingleFilmReference(double lambdaNm, double cosThetaIncident, double incidentIor,
                                        const Layer& film, complexd substrateIor) {
    AmpRT out[2];
    for (int k = 0; k < 2; ++k) {
        const FilmInterfaces f =
            filmInterfaces(k == 0 ? Pol::S : Pol::P, lambdaNm, cosThetaIncident, incidentIor, film, substrateIor);
        // Airy sum (Born & Wolf §1.6.4): r = (r01 + r12 E)/(1 + r01 r12 E), Σ = 1/(1 + r01 r12 E).
        const complexd den = 1.0 + f.r01 * f.r12 * f.E;
        out[k].r = (f.r01 + f.r12 * f.E) / den;
        out[k].T = transmittance(f, 1.0 / den);
    }
    return combine(out[0], out[1], true);
}

ThinFilmStackResult truncatedSingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor,
                                    const Layer& film, complexd substrateIor, int K) {
    K = std::max(K, 0);
    AmpRT out[2];
    for (int k = 0; k < 2; ++k) {
        const FilmInterfaces f =
            filmInterfaces(k == 0 ? Pol::S : Pol::P, lambdaNm, cosThetaIncident, incidentIor, film, substrateIor);
        // Partial geometric series Σ_{m=0}^{K−1} (r10 r12 E)^m with r10 = −r01 (Heavens ch. 4):
        // r_K = r01 + t01 t10 r12 E Σ,  t01 t10 = 1 − r01²;  t_K = t01 t12 e^{iδ} Σ.
        const complexd ratio = -f.r01 * f.r12 * f.E;
        complexd sum = 0.0, term = 1.0;
        for (int m = 0; m < K; ++m) {
            sum += term;
            term *= ratio;
        }
        out[k].r = f.r01 + (1.0 - f.r01 * f.r01) * f.r12 * f.E * sum;
        out[k].T = transmittance(f, sum);
    }
    return combine(out[0], out[1], false);
}

ThinFilmStackResult incoherentSingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor,
                                     const Layer& film, complexd substrateIor) {
    double R[2], T[2];
    for (int k = 0; k < 2; ++k) {
        const FilmInterfaces f =
            filmInterfaces(k == 0 ? Pol::S : Pol::P, lambdaNm, cosThetaIncident, incidentIor, film, substrateIor);
        const double R01 = std::min(1.0, std::norm(f.r01)), R12 = std::min(1.0, std::norm(f.r12));
        const double a = std::norm(f.halfPhase);  // single-pass attenuation e^{−2 Im δ}
        const double T01 = 1.0 - R01, T12 = 1.0 - R12;
        // Heavens ch. 4: intensities of all internally reflected beams summed without phase.
        const double loop = R01 * R12 * a * a;  // R10 = R01
        const double den = 1.0 - loop;
        if (den <= 0) {  // both interfaces totally reflecting and lossless: nothing enters
            R[k] = 1.0;
            T[k] = 0.0;
            continue;
        }
        R[k] = std::min(1.0, R01 + T01 * T01 * R12 * a * a / den);
        T[k] = std::clamp(T01 * T12 * a / den, 0.0, 1.0 - R[k]);
    }
    return ThinFilmStackResult{R[0], R[1], T[0], T[1]};
}

ThinFilmStackResult singleFilmRT(ThinFilmPhaseMode mode, int K, double lambdaNm, double cosThetaIncident, double incidentIor,
                             const Layer& film, complexd substrateIor) {
    switch (mode) {
        case ThinFilmPhaseMode::Exact: return airySingleFilm(lambdaNm, cosThetaIncident, incidentIor, film, substrateIor);
        case ThinFilmPhaseMode::Truncated:
            return truncatedSingleFilm(lambdaNm, cosThetaIncident, incidentIor, film, substrateIor, K);
        case ThinFilmPhaseMode::Incoherent:
            return incoherentSingleFilm(lambdaNm, cosThetaIncident, incidentIor, film, substrateIor);
    }
    return {};
}

}  // namespace iris
