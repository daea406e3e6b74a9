#include "materials/thin_film_mueller.h"

#include "materials/mueller_frames.h"

namespace iris {

namespace {

/// The interface layout [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]] per wavelength
/// from each entry's powers P_s, P_p and cross term C + iD (spectral/thin_film_polarization.h).
template <typename Terms>
MuellerSpectrum layout(int n, Terms&& terms) {
    SampledSpectrum A(n), B(n), C(n), D(n);
    for (int k = 0; k < n; ++k) {
        double ps, pp;
        complexd cross;
        terms(k, ps, pp, cross);
        A[k] = float(0.5 * (ps + pp));
        B[k] = float(0.5 * (ps - pp));
        C[k] = float(cross.real());
        D[k] = float(cross.imag());
    }
    return mueller::interfaceMueller(A, B, C, D);
}

}  // namespace

MuellerSpectrum coatingReflectionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                         const vec3& wo) {
    ThinFilmCoating::PolarizationLanes p;
    c.polarizationAll(cosTheta, below, p);  // all wavelengths at once (the batched kernel)
    const MuellerSpectrum M = layout(c.size(), [&](int k, double& ps, double& pp, complexd& cross) {
        ps = p.Rs[k], pp = p.Rp[k], cross = complexd(p.crossRRe[k], p.crossRIm[k]);
    });
    return fromSAxisBases(M, m, wi, wo);
}

MuellerSpectrum coatingTransmissionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                           const vec3& wo) {
    ThinFilmCoating::PolarizationLanes p;
    c.polarizationAll(cosTheta, below, p);
    const MuellerSpectrum M = layout(c.size(), [&](int k, double& ps, double& pp, complexd& cross) {
        ps = p.Ts[k], pp = p.Tp[k], cross = complexd(p.crossTRe[k], p.crossTIm[k]);
    });
    return fromSAxisBases(M, m, wi, wo);
}

MuellerSpectrum coatingDiffuseMueller(const ThinFilmCoating& c, const SampledSpectrum& base, const vec3& wi, const vec3& wo) {
    const int n = c.size();
    MuellerSpectrum M(n);
    ThinFilmCoating::PolarizationLanes pin, pout;
    c.polarizationPowersAll(wi.z, false, pin);
    c.polarizationPowersAll(wo.z, false, pout);
    for (int k = 0; k < n; ++k) {
        const ThinFilmStackResult in{pin.Rs[k], pin.Rp[k], pin.Ts[k], pin.Tp[k]}, out{pout.Rs[k], pout.Rp[k], pout.Ts[k], pout.Tp[k]};
        // T is reciprocal per polarization: the exit through the stack at θo has the T_s, T_p of the
        // entry at θo (Born & Wolf §1.5; Mitsuba 3 pplastic.cpp: Ti · depolarizer · To).
        const double ai = 0.5 * (in.Ts + in.Tp), bi = 0.5 * (in.Ts - in.Tp);
        const double ao = 0.5 * (out.Ts + out.Tp), bo = 0.5 * (out.Ts - out.Tp);
        M(0, 0)[k] = float(base[k] * ao * ai);
        M(0, 1)[k] = float(base[k] * ao * bi);
        M(1, 0)[k] = float(base[k] * bo * ai);
        M(1, 1)[k] = float(base[k] * bo * bi);
    }
    return fromSAxisBases(M, vec3(0, 0, 1), wi, wo);
}

}  // namespace iris
