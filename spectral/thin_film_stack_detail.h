// The transfer-matrix and single-film internals of spectral/thin_film_stack.cpp, shared with the
// polarized mode's amplitude terms (spectral/thin_film_polarization.cpp): the admittances, the
// scaled characteristic-matrix product and the interface coefficients of one film
// (docs/thin_film.md §2, §3 for the numerics).
#pragma once

#include <span>

#include "spectral/thin_film_stack.h"

namespace iris::thin_film_detail {

enum class Pol { S, P };

/// Tilted admittance used for polarisation `pol` (Macleod ch. 2): y_s = q, y_p = q/ñ² (the p form
/// is the impedance of the tangential H field; both give Born & Wolf's r_s, r_p as (y_i−y_j)/(y_i+y_j)).
inline complexd admittance(Pol pol, complexd q, complexd ior) { return pol == Pol::S ? q : q / (ior * ior); }

/// e^{z} − 1 without cancellation for small |z|.
complexd expm1c(complexd z);
/// (e^{2iδ} − 1)/(2q) with δ = k0 q d, finite as q → 0 (limit i k0 d).
complexd halfExpm1OverQ(complexd q, double k0d);

/// Complex amplitudes of one polarisation for the transfer-matrix method: r, T, and the tangential
/// transmission coefficient t (the substrate's tangential field — E for s, H for p — per unit
/// incident one; its phase is the transmitted wave's for real incident and substrate indices).
struct AmpRT {
    complexd r;
    double T;
    complexd t;
};

/// Both polarisations through the layers (top → bottom) onto the substrate; y0: the incident
/// admittances for s and p, s: the invariant n0 sin θ0. out[0] is s, out[1] p.
void transferMatrix(double lambdaNm, const double y0[2], double s, std::span<const Layer> layers, complexd substrateIor,
                    AmpRT out[2]);

/// Everything the single-film sums need for one polarisation.
struct FilmInterfaces {
    complexd r01, r12;
    complexd tScaled;           // t01 t12 / y0, so T = y0 Re(y2) |tScaled e^{iδ} Σ|²
    complexd E;                 // e^{2iδ}
    complexd halfPhase;         // e^{iδ}
    double y0;
    complexd y2;
};

FilmInterfaces filmInterfaces(Pol pol, double lambdaNm, double cosThetaIncident, double incidentIor,
                              const Layer& film, complexd substrateIor);

}  // namespace iris::thin_film_detail
