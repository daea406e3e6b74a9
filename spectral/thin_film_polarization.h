// A film stack's polarization terms (polarized mode, docs/polarization.md): what the Mueller
// matrices of its reflection and transmission need besides the s and p powers — the cross terms
// C + iD of the interface layout (spectral/mueller.h mueller::interfaceMueller):
//   reflection:   C + iD = r_s r_p*                      (|C + iD|² = R_s R_p for coherent sums)
//   transmission: C + iD = √(T_s T_p) · t_s t_p* / |t_s t_p*|
// from the stack's complex amplitudes in iris's conventions (docs/thin_film.md §1: e^{−iωt},
// ñ = n + ik, Born & Wolf's r_p), which is Mitsuba 3's a_p a_s* (its mueller::specular_reflection
// with e^{+iωt} amplitudes). The incoherent phase mode sums the Mueller matrices of the beams
// (Heavens ch. 4's series for the cross terms as for the powers), which partially depolarizes.
#pragma once

#include <span>

#include "spectral/thin_film_stack.h"

namespace iris {

struct AiryAngle;  // spectral/thin_film_airy.h

struct FilmPolarization {
    ThinFilmStackResult power;       // R_s, R_p, T_s, T_p (as thinFilmStackRT / singleFilmRT)
    complexd crossR{0.0, 0.0};       // C + iD of the reflection
    complexd crossT{0.0, 0.0};       // C + iD of the transmission
};

/// The powers as the polarized mode uses them: R ∈ [0, 1], T ∈ [0, 1 − R] per polarization.
ThinFilmStackResult clampedPowers(ThinFilmStackResult r);
/// clampedPowers, and each cross term scaled down to at most √(P_s P_p) of the clamped powers
/// (its magnitude for a coherent sum), so that the Mueller matrix stays physical.
FilmPolarization clampedPolarization(FilmPolarization p);

/// Complex amplitudes of a stack by the transfer-matrix method (any number of layers): the
/// reflection amplitudes r_s, r_p and the tangential transmission coefficients t_s, t_p.
struct StackAmplitudes {
    complexd rs, rp, ts, tp;
    ThinFilmStackResult power;
};
StackAmplitudes thinFilmStackAmplitudes(double lambdaNm, double cosThetaIncident, double incidentIor,
                                        std::span<const Layer> layers, complexd substrateIor);

/// The terms of an exact (coherent, all round trips) stack of any number of layers.
FilmPolarization stackPolarization(double lambdaNm, double cosThetaIncident, double incidentIor, std::span<const Layer> layers,
                                   complexd substrateIor);
/// The terms of an exact single film from the closed-form Airy sum (spectral/thin_film_airy.h
/// airySingleFilmTerms, the spectral mode's kernel): its powers (clamped as airySingleFilmFastAt
/// clamps them), C + iD = r_s r_p* with r = num/den, and √(T_s T_p) times the phase of t_s t_p*,
/// t = 4 y0 y1 e^{iδ}/den, whose factor 4 y0 e^{iδ} (y0 > 0 real, δ the same for s and p) drops
/// out of the phase. Declines exactly where airySingleFilmFastAt does (the caller then uses stackPolarization,
/// the transfer matrix, as airySingleFilm falls back to thinFilmStackRT).
bool airySingleFilmPolarizationAt(const AiryAngle& angle, const AiryFilmConstants& film, const SquaredIndex& substrate,
                                  FilmPolarization& out);

/// The terms of one film in a phase mode (docs/thin_film.md §2); K is used by Truncated only. Exact:
/// airySingleFilmPolarizationAt, else stackPolarization (as singleFilmRT evaluates airySingleFilm). The
/// truncated sums' powers are clamped as the materials clamp them (R ≤ 1, T ≤ 1 − R), the cross
/// terms scaled to match.
FilmPolarization singleFilmPolarization(ThinFilmPhaseMode mode, int K, double lambdaNm, double cosThetaIncident,
                                        double incidentIor, const Layer& film, complexd substrateIor);

}  // namespace iris
