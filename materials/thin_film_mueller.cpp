#include "materials/thin_film_mueller.h"

#include "materials/mueller_frames.h"
#include "spectral/spectrum_lanes.h"

// Double4 values pass only between always-inline lane functions (spectral/lanes.h): GCC's note on
// the ABI of 32-byte vectors without AVX concerns calls that never happen.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace iris {

namespace {

using lanes::Double4;
using lanes::Float4;

using lanes::storeGroup;  // four lanes at a time: no scalar stores that vector loads read back
/// v where lane l + i < n, 0 in the padding lanes (the terms there are unspecified).
Float4 inEntries(Float4 v, int l, int n) { return lanes::select<Float4>(lanes::entryLanes(l, n), v, Float4{}); }

/// The interface layout [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]] per wavelength
/// from each entry's powers P_s, P_p and cross term C + iD (spectral/thin_film_polarization.h;
/// A = (P_s + P_p)/2, B = (P_s − P_p)/2: Mitsuba 3 mueller::specular_reflection), structure of
/// arrays as ThinFilmCoating::PolarizationLanes, four entries at a time.
MuellerSpectrum layout(int n, const double* ps, const double* pp, const double* re, const double* im) {
    SampledSpectrum A(n), B(n), C(n), D(n);
    const Double4 half = lanes::broadcast(0.5);
    for (int l = 0; l < n; l += SampledSpectrum::kLanes) {
        const Double4 s = lanes::load(ps + l), p = lanes::load(pp + l);
        storeGroup(A, l, inEntries(lanes::toFloat(half * (s + p)), l, n));
        storeGroup(B, l, inEntries(lanes::toFloat(half * (s - p)), l, n));
        storeGroup(C, l, inEntries(lanes::toFloat(lanes::load(re + l)), l, n));
        storeGroup(D, l, inEntries(lanes::toFloat(lanes::load(im + l)), l, n));
    }
    return mueller::interfaceMueller(A, B, C, D);
}

}  // namespace

MuellerSpectrum coatingReflectionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                         const vec3& wo) {
    ThinFilmCoating::PolarizationLanes p;
    c.polarizationAll(cosTheta, below, p);  // all wavelengths at once (the batched kernel)
    const MuellerSpectrum M = layout(c.size(), p.Rs, p.Rp, p.crossRRe, p.crossRIm);
    return fromSAxisBases(M, m, wi, wo);
}

MuellerSpectrum coatingTransmissionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                           const vec3& wo) {
    ThinFilmCoating::PolarizationLanes p;
    c.polarizationAll(cosTheta, below, p);
    const MuellerSpectrum M = layout(c.size(), p.Ts, p.Tp, p.crossTRe, p.crossTIm);
    return fromSAxisBases(M, m, wi, wo);
}

MuellerSpectrum coatingDiffuseMueller(const ThinFilmCoating& c, const SampledSpectrum& base, const vec3& wi, const vec3& wo) {
    const int n = c.size();
    MuellerSpectrum M(n);
    ThinFilmCoating::PolarizationLanes pin, pout;
    c.polarizationPowersAll(wi.z, false, pin);
    c.polarizationPowersAll(wo.z, false, pout);
    // T is reciprocal per polarization: the exit through the stack at θo has the T_s, T_p of the
    // entry at θo (Born & Wolf §1.5; Mitsuba 3 pplastic.cpp: Ti · depolarizer · To). Four entries
    // at a time, in double as the per-entry form: base · a_o · a_i etc. with a = (T_s + T_p)/2,
    // b = (T_s − T_p)/2.
    const Double4 half = lanes::broadcast(0.5);
    for (int l = 0; l < n; l += SampledSpectrum::kLanes) {
        const Double4 tsi = lanes::load(pin.Ts + l), tpi = lanes::load(pin.Tp + l);
        const Double4 tso = lanes::load(pout.Ts + l), tpo = lanes::load(pout.Tp + l);
        const Double4 ai = half * (tsi + tpi), bi = half * (tsi - tpi), ao = half * (tso + tpo), bo = half * (tso - tpo);
        const Double4 b = lanes::toDouble(lanes::loadGroup(base, l));
        storeGroup(M(0, 0), l, inEntries(lanes::toFloat(b * ao * ai), l, n));
        storeGroup(M(0, 1), l, inEntries(lanes::toFloat(b * ao * bi), l, n));
        storeGroup(M(1, 0), l, inEntries(lanes::toFloat(b * bo * ai), l, n));
        storeGroup(M(1, 1), l, inEntries(lanes::toFloat(b * bo * bi), l, n));
    }
    return fromSAxisBases(M, vec3(0, 0, 1), wi, wo);
}

}  // namespace iris
