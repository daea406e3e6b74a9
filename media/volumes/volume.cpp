#include "media/volumes/volume.h"

#include <cmath>
#include <limits>

#include "spectral/spectrum_params.h"

namespace iris {

bool Box3::clip(const Ray& ray, float tMax, float& t0, float& t1) const {
    // Slab method (Kay & Kajiya 1986; pbrt-v4 §6.1.2 Bounds3::IntersectP): intersect [0, tMax]
    // with each axis' interval of t; an axis the ray runs parallel to either contains the origin
    // (no constraint) or misses.
    t0 = 0.0f;
    t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        if (ray.d[a] == 0.0f) {
            if (ray.o[a] < lo[a] || ray.o[a] > hi[a]) return false;
            continue;
        }
        const float inv = 1.0f / ray.d[a];
        float tNear = (lo[a] - ray.o[a]) * inv, tFar = (hi[a] - ray.o[a]) * inv;
        if (tNear > tFar) std::swap(tNear, tFar);
        t0 = std::max(t0, tNear);
        t1 = std::min(t1, tFar);
        if (!(t0 <= t1)) return false;  // also rejects NaN
    }
    return true;
}

Box3 transformBox(const mat4& m, const Box3& b) {
    Box3 r{vec3(std::numeric_limits<float>::infinity()), vec3(-std::numeric_limits<float>::infinity())};
    for (int c = 0; c < 8; ++c) {
        const vec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
        const vec3 q = transformPoint(m, corner);
        r.lo = glm::min(r.lo, q);
        r.hi = glm::max(r.hi, q);
    }
    return r;
}

Volume::Volume(const mat4& toWorld)
    : toWorld_(toWorld), toLocal_(glm::inverse(toWorld)),
      bounds_(transformBox(toWorld, Box3{vec3(0.0f), vec3(1.0f)})) {}  // Mitsuba 3 Volume::update_bbox

mat4 readToWorld(const Properties& p) {
    const mat4 m = p.getTransform("to_world", mat4(1.0f));
    bool finite = true;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(m[c][r]);
    const float det = glm::determinant(mat3(m));
    if (!finite || !std::isfinite(det) || std::abs(det) < 1e-30f)
        failAt(p.locationOf("to_world"), p.tag(), " '", p.type(), "': to_world must be an invertible, finite transform");
    return m;
}

VolumePtr getVolume(const Properties& p, const std::string& name, SpectrumKind kind, float def) {
    if (!p.present(name)) return makeConstVolume(spectrumFromNumber(def, kind));
    const Properties::Entry& e = p.require(name);
    if (const PropertiesPtr* obj = std::get_if<PropertiesPtr>(&e.value); obj && (*obj)->tag() != "spectrum") {
        if ((*obj)->tag() != "volume")
            failAt(e.loc, "parameter '", name, "' must be a volume or spectrum, not a ", (*obj)->tag());
        VolumePtr v = VolumeRegistry::instance().create(**obj, kind);
        if (v->channels() != 0 && v->channels() != 1 && v->channels() != 3)
            failAt(e.loc, "parameter '", name, "': a ", (*obj)->type(), " of ", v->channels(),
                   " channels cannot give a spectrum (it needs 1 or 3 channels)");
        return v;
    }
    return makeConstVolume(getSpectrum(p, name, kind));  // a number, <rgb>, <spectrum> or spectrum plugin
}

float FloatVolume::eval(const vec3& p) const {
    if (!volume) return constant;
    float v = 0.0f;
    volume->evalChannels(p, &v);
    return v;
}

ValueRange FloatVolume::range() const { return volume ? volume->range() : ValueRange{constant, constant}; }

VolumePtr getChannelVolume(const Properties& p, const std::string& name, int channels) {
    const Properties::Entry& e = p.require(name);
    const PropertiesPtr* obj = std::get_if<PropertiesPtr>(&e.value);
    const std::string want = strCat(channels, channels == 1 ? " channel" : " channels");
    if (!obj || (*obj)->tag() != "volume") failAt(e.loc, "parameter '", name, "' must be a <volume> of ", want);
    VolumePtr v = VolumeRegistry::instance().create(**obj, SpectrumKind::Unbounded);
    if (v->channels() != channels)
        failAt(e.loc, "parameter '", name, "' must be a volume of ", want, ", this ", (*obj)->type(), " has ", v->channels(),
               v->channels() == 0 ? " (a spectrum)" : "");
    return v;
}

FloatVolume getFloatVolume(const Properties& p, const std::string& name, float def) {
    if (!p.present(name)) return FloatVolume{def, nullptr};
    const Properties::Entry& e = p.require(name);
    if (const PropertiesPtr* obj = std::get_if<PropertiesPtr>(&e.value); obj && (*obj)->tag() == "volume")
        return FloatVolume{0.0f, getChannelVolume(p, name, 1)};
    return FloatVolume{p.getFloat(name), nullptr};
}

}  // namespace iris
