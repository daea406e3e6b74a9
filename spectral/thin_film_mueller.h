// A film stack's Mueller matrices in double precision (polarized mode, docs/polarization.md; the
// Python module's iris.thin_film.stack_mueller): the interface layout of spectral/mueller.h in
// s-axis bases from the stack's powers and cross terms (spectral/thin_film_polarization.h),
//   [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]],
// A = (P_s + P_p)/2, B = (P_s − P_p)/2, C + iD the cross term (Mitsuba 3 mueller.h
// specular_reflection's layout).
#pragma once

#include "spectral/thin_film_polarization.h"

namespace iris {

struct Mueller4d {
    double m[4][4] = {};
};

inline Mueller4d interfaceMueller4d(double ps, double pp, complexd cross) {
    const double a = 0.5 * (ps + pp), b = 0.5 * (ps - pp);
    Mueller4d r;
    r.m[0][0] = r.m[1][1] = a;
    r.m[0][1] = r.m[1][0] = b;
    r.m[2][2] = r.m[3][3] = cross.real();
    r.m[2][3] = -cross.imag();
    r.m[3][2] = cross.imag();
    return r;
}
inline Mueller4d reflectionMueller(const FilmPolarization& p) { return interfaceMueller4d(p.power.Rs, p.power.Rp, p.crossR); }
inline Mueller4d transmissionMueller(const FilmPolarization& p) { return interfaceMueller4d(p.power.Ts, p.power.Tp, p.crossT); }

}  // namespace iris
