#include "materials/mueller_frames.h"

#include "spectral/stokes_basis.h"

namespace iris {
namespace {

vec3 normalizedOr(const vec3& v, const vec3& fallback) {
    const float l2 = glm::dot(v, v);
    return l2 > 0 ? v / std::sqrt(l2) : fallback;
}

/// Q M Q, Q = diag(1, 1, −1, −1): the entries with exactly one index in {2, 3} change sign.
MuellerSpectrum mirrorHandedness(MuellerSpectrum m) {
    if (m.depolarizing()) return m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if ((i >= 2) != (j >= 2)) m(i, j) = -m(i, j);
    return m;
}

}  // namespace

MuellerSpectrum fromSAxisBases(const MuellerSpectrum& m, const vec3& normal, const vec3& wi, const vec3& wo) {
    if (m.depolarizing()) return m;
    const vec3 sIn0 = glm::cross(normal, -wi);
    const bool collinear = glm::dot(sIn0, sIn0) == 0;
    const vec3 sIn = collinear ? vec3(1, 0, 0) : glm::normalize(sIn0);
    const vec3 sOut = collinear ? vec3(1, 0, 0) : normalizedOr(glm::cross(normal, wo), vec3(1, 0, 0));
    return toImplicitBases(m, -wi, sIn, wo, sOut);
}

MuellerSpectrum fromNestedFrame(const MuellerSpectrum& nested, const Frame& f, bool mirrored, const vec3& wi, const vec3& wo) {
    if (nested.depolarizing()) return nested;
    // The nested bases, stokesBasis of the nested-local directions, mapped to this frame.
    const vec3 inCur = f.toWorld(stokesBasis(f.toLocal(-wi))), outCur = f.toWorld(stokesBasis(f.toLocal(wo)));
    const MuellerSpectrum m = mirrored ? mirrorHandedness(nested) : nested;
    return toImplicitBases(m, -wi, inCur, wo, outCur);
}

}  // namespace iris
