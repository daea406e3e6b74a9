// Exact optics of thin-film stacks at one wavelength, in double precision with complex indices.
//
// Conventions (see docs/thin_film.md): time dependence e^{−iωt}, complex index ñ = n + ik with
// k ≥ 0 meaning absorption, so a plane wave exp(i(k0 ñ·r − ωt)) decays when Im(ñ) > 0. For a
// stack lit from a real incident medium n0 at angle θ0 the conserved tangential invariant is
// s = n0 sinθ0 and every layer j has the normal wave number (divided by k0 = 2π/λ)
//     q_j = ñ_j cosθ_j = sqrt(ñ_j² − s²),  branch Im(q_j) ≥ 0   (Born & Wolf §1.5, ch. 14)
// so evanescent and absorbed waves decay into each layer. Tilted optical admittances
// (Macleod, "Thin-Film Optical Filters", 4th ed., ch. 2): y_s = q, y_p = q/ñ² (the p case is
// written with the impedance of the tangential H field, which never divides by q and stays
// finite at grazing incidence and at the critical angle). Every interface coefficient and the
// characteristic matrices are expressed with these y.
//
// Intensity results (R, T) are for s and p separately; unpolarised light is their mean.
// T is the power fraction entering the substrate (for an absorbing substrate: what it absorbs).
#pragma once

#include <complex>
#include <span>

namespace iris {

using complexd = std::complex<double>;

/// 2π in double precision (film phases k0 d = 2π d/λ).
constexpr double kTwoPi = 6.283185307179586476925286766559;

/// One homogeneous layer: complex index ñ = n + ik at the wavelength considered, thickness in nm.
struct Layer {
    complexd ior;
    double thicknessNm = 0.0;
};

/// Reflectance / transmittance of a stack for s and p polarisation (powers, not amplitudes).
struct ThinFilmStackResult {
    double Rs = 0, Rp = 0, Ts = 0, Tp = 0;
    double R() const { return 0.5 * (Rs + Rp); }  // unpolarised: mean of s and p
    double T() const { return 0.5 * (Ts + Tp); }
    double A() const { return 1.0 - R() - T(); }  // absorbed in the layers (≈0 for lossless stacks)
};

/// Amplitude Fresnel coefficients of one planar interface i→j (Born & Wolf §1.5.2, Fresnel formulae),
/// for the electric-field amplitudes: r_s = (q_i − q_j)/(q_i + q_j), t_s = 2q_i/(q_i + q_j),
/// r_p = (ñ_j² q_i − ñ_i² q_j)/(ñ_j² q_i + ñ_i² q_j), t_p = 2 ñ_i ñ_j q_i/(ñ_j² q_i + ñ_i² q_j).
/// (Born & Wolf's sign convention for r_p: r_p = r_s at normal incidence.)
struct FresnelAmplitudes {
    complexd rs, rp, ts, tp;
};

/// q = ñ cosθ = sqrt(ñ² − s²) with the decaying branch Im(q) ≥ 0 (and Re(q) ≥ 0 when Im(q) = 0).
complexd normalWaveNumber(complexd ior, double sinInvariant);

/// Interface amplitudes for light in a medium with index `iorI` (real) at cosθi onto `iorT`.
FresnelAmplitudes fresnelAmplitudes(double cosThetaI, double iorI, complexd iorT);
/// Power reflectance of one interface (|r_s|², |r_p|²) and transmittance into `iorT`
/// (Re(y_t)/y_i |t|², zero beyond the critical angle). Equals thinFilmStackRT with no layers.
ThinFilmStackResult fresnelInterfaceRT(double cosThetaI, double iorI, complexd iorT);

/// Transfer-matrix (characteristic-matrix) method for any number of layers, top→bottom
/// (Born & Wolf §1.6.2–1.6.4, Macleod ch. 2). `cosThetaIncident` ∈ [0,1] in the real incident medium
/// `incidentIor` (> 0, may be denser than the substrate: total internal reflection is handled).
/// Each layer matrix is scaled by e^{iδ_j} so that only e^{2iδ_j}, |e^{2iδ_j}| ≤ 1, appears
/// (never e^{+κd}); the running vector is renormalised and its log scale tracked for T.
ThinFilmStackResult thinFilmStackRT(double lambdaNm, double cosThetaIncident, double incidentIor,
                            std::span<const Layer> layers, complexd substrateIor);

/// How the internal reflections of a single film are summed (docs/thin_film.md §Phase modes).
enum class ThinFilmPhaseMode {
    Exact,       // coherent Airy sum to infinity (closed form)
    Truncated,   // coherent sum keeping beams that cross the film at most 2K times
    Incoherent,  // phase-averaged sum of intensities
};

/// Closed-form Airy summation for one film (Born & Wolf §1.6.4; Heavens,
/// "Optical Properties of Thin Solid Films", ch. 4):  r = (r01 + r12 e^{2iδ})/(1 + r01 r12 e^{2iδ}),
/// t = t01 t12 e^{iδ}/(1 + r01 r12 e^{2iδ}),  δ = 2π ñ1 d cosθ1 / λ.
/// Evaluated by airySingleFilmFast (below); where that declines, by the transfer matrix (thinFilmStackRT).
ThinFilmStackResult airySingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor, const Layer& film,
                               complexd substrateIor);

/// The original formulation of airySingleFilm (complex interface coefficients r01, r12 and
/// std::complex division). Kept as the reference the fast path is tested against (and for the
/// benchmark's before/after figure); the renderer does not call it.
ThinFilmStackResult airySingleFilmReference(double lambdaNm, double cosThetaIncident, double incidentIor,
                                        const Layer& film, complexd substrateIor);

/// Angle-independent part of the exact Airy sum at one wavelength, hoisted out of per-evaluation
/// code (ThinFilmCoating keeps one per path wavelength): film ñ1², 1/ñ1² and k0 d = 2π d/λ.
struct AiryFilmConstants {
    complexd n1sq, invN1sq;
    double k0d = 0;
};
/// Squared index and its reciprocal (for the p admittance y_p = q/ñ²), in real arithmetic.
struct SquaredIndex {
    complexd sq, inv;
};
SquaredIndex squaredIndex(complexd ior);
AiryFilmConstants airyFilmConstants(double lambdaNm, const Layer& film);
/// The same from an already squared film index.
AiryFilmConstants airyFilmConstants(double lambdaNm, double thicknessNm, const SquaredIndex& n1);

/// Fast exact Airy sum (docs/thin_film.md §8): s and p from one q1, q2 and one sin/cos pair;
/// no complex division. With P = 1 + e^{2iδ}, M = 1 − e^{2iδ} (from the half angle, no cancellation)
/// the Airy sum multiplied through by (y0 + y1)(y1 + y2) is
///   r = [y1 (y0 − y2) P + (y0 y2 − y1²) M] / den,   den = y1 (y0 + y2) P + (y0 y2 + y1²) M,
///   T = 16 y0 Re(y2) |y1|² |e^{2iδ}| / |den|²,
/// so R and T need one real division each; e^{iδ} enters T only through |e^{iδ}|² = |e^{2iδ}|. This
/// form stays accurate at the film's critical angle (y1 → 0 and M → 0 together), where the
/// r01/r12 form (airySingleFilmReference) is 0/0. q1, q2 take a real square root when their
/// radicand is real (lossless film or substrate: real below the critical angle, imaginary beyond).
/// Returns false (out untouched) when den vanishes or underflows (q1 = 0 exactly) or a result is
/// not finite; airySingleFilm then uses the transfer matrix. Tested against the transfer matrix
/// and the reference in tests/materials/test_thin_film_fast.cpp.
bool airySingleFilmFast(double cosThetaIncident, double incidentIor, const AiryFilmConstants& film,
                        const SquaredIndex& substrate, ThinFilmStackResult& out);

/// Coherent sum truncated after K ≥ 0 round trips: reflection keeps the direct beam and K beams
/// that made 1..K round trips (K = 1: two-beam interference), transmission the K beams with
/// 0..K−1 round trips (K = 0 gives T = 0). Not energy conserving for finite K: R may exceed 1
/// for strongly reflecting interfaces; callers that need a reflectance clamp it.
ThinFilmStackResult truncatedSingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor,
                                    const Layer& film, complexd substrateIor, int K);

/// Incoherent (phase-averaged) sum of intensities with the film's single-pass attenuation
/// a = |e^{iδ}|² = e^{−2 Im δ}:  R = R01 + T01 T10 R12 a² / (1 − R10 R12 a²),
/// T = T01 T12 a / (1 − R10 R12 a²)  (Heavens ch. 4; Macleod ch. 2 on thick incoherent layers). Interface transmittances are
/// 1 − R (exact for a lossless film; for an absorbing film the standard approximation).
ThinFilmStackResult incoherentSingleFilm(double lambdaNm, double cosThetaIncident, double incidentIor,
                                     const Layer& film, complexd substrateIor);

/// Dispatch on the phase mode (K is used by Truncated only).
ThinFilmStackResult singleFilmRT(ThinFilmPhaseMode mode, int K, double lambdaNm, double cosThetaIncident, double incidentIor,
                             const Layer& film, complexd substrateIor);

}  // namespace iris
