#include "render/lights/area_light.h"

#include "core/frame.h"

namespace iris {

AreaLight::AreaLight(const TriangleMesh* mesh, SpectrumTexturePtr radiance)
    : kind_(Kind::Mesh), mesh_(mesh), radiance_(std::move(radiance)) {
    std::vector<float> areas(mesh->triangleCount());
    for (size_t i = 0; i < areas.size(); ++i) {
        const vec3& a = mesh->positions[mesh->indices[3 * i]];
        const vec3& b = mesh->positions[mesh->indices[3 * i + 1]];
        const vec3& c = mesh->positions[mesh->indices[3 * i + 2]];
        areas[i] = 0.5f * glm::length(glm::cross(b - a, c - a));
        area_ += areas[i];
    }
    triangles_ = Distribution1D(areas);
}

AreaLight::AreaLight(const vec3& center, float radius, const mat3& frame, bool inward, SpectrumTexturePtr radiance)
    : kind_(Kind::Sphere), center_(center), radius_(radius), frame_(frame), inward_(inward), area_(4.0f * kPi * radius * radius),
      radiance_(std::move(radiance)) {}

AreaLight::AreaLight(const CylinderGeometry& cylinder, float radius, bool inward, SpectrumTexturePtr radiance)
    : kind_(Kind::Cylinder), cylinder_(cylinder), radius_(radius), inward_(inward),
      area_(2.0f * kPi * radius * cylinder.length), radiance_(std::move(radiance)) {}

void AreaLight::sampleArea(const vec2& u, TextureQuery& at, vec3& n) const {
    if (kind_ == Kind::Cylinder) {
        // Mitsuba 3 Cylinder::sample_position: φ = 2π u.y, position u.x · length along the axis.
        const CylinderGeometry& c = cylinder_;
        const float phi = 2 * kPi * u.y;
        const vec3 radial = std::cos(phi) * c.s + std::sin(phi) * c.t;
        at.p = c.p0 + u.x * c.length * c.axis + radius_ * radial;
        n = inward_ ? -radial : radial;
        at.uv = vec2(u.y, u.x);  // the cylinder's uv (render/scene.cpp): φ/2π, position / length
        return;
    }
    // Pick a triangle by area, then a point on it (pdf_A = 1/A).
    float uRemapped;
    const int tri = triangles_.sampleDiscrete(u.x, nullptr, &uRemapped);
    const vec2 b = sampleUniformTriangle(vec2(uRemapped, u.y));
    const uint32_t* idx = &mesh_->indices[3 * tri];
    const vec3 &a = mesh_->positions[idx[0]], &bb = mesh_->positions[idx[1]], &c = mesh_->positions[idx[2]];
    at.p = b.x * a + b.y * bb + (1 - b.x - b.y) * c;
    n = glm::normalize(glm::cross(bb - a, c - a));
    vec2 corner[3];  // the uv the scene gives a hit there (render/scene.cpp)
    mesh_->cornerUVs(size_t(tri), corner);
    at.uv = b.x * corner[0] + b.y * corner[1] + (1 - b.x - b.y) * corner[2];
    // The hit's barycentrics there (weights of corners 1 and 2), for mesh attributes.
    at.mesh = mesh_;
    at.triangle = uint32_t(tri);
    at.bary = vec2(b.y, 1 - b.x - b.y);
}

SampledSpectrum AreaLight::Le(const TextureQuery& at, const vec3& n, const vec3& w, const SampledWavelengths& wl) const {
    if (glm::dot(n, w) <= 0) return SampledSpectrum(wl.size());  // one-sided emitter
    return radiance_->eval(at, wl);
}

std::optional<LightSample> AreaLight::sampleLi(const vec3& p, const vec2& u, const SampledWavelengths& wl) const {
    LightSample ls;
    TextureQuery at;  // the sampled point as the radiance texture sees it
    if (kind_ != Kind::Sphere) {
        // Uniform area sampling (pdf_A = 1/A), converted to solid angle.
        sampleArea(u, at, ls.nLight);
        ls.pLight = at.p;
        ls.uv = at.uv;
        const vec3 d = ls.pLight - p;
        const float dist2 = glm::dot(d, d);
        if (dist2 <= 0) return std::nullopt;
        ls.wi = d / std::sqrt(dist2);
        const float cosL = std::abs(glm::dot(ls.nLight, ls.wi));
        if (cosL <= 1e-8f) return std::nullopt;
        ls.pdf = dist2 / (cosL * area_);  // area → solid angle
    } else {
        const vec3 toC = center_ - p;
        const float dc2 = glm::dot(toC, toC);
        if (dc2 <= radius_ * radius_ * 1.00001f) {
            // Inside (or on) the sphere: uniform area sampling.
            const vec3 n = sampleUniformSphere(u);
            ls.pLight = center_ + radius_ * n;
            ls.nLight = inward_ ? -n : n;
            ls.uv = sphereUV(glm::transpose(frame_) * n);
            const vec3 d = ls.pLight - p;
            const float dist2 = glm::dot(d, d);
            if (dist2 <= 0) return std::nullopt;
            ls.wi = d / std::sqrt(dist2);
            const float cosL = std::abs(glm::dot(n, ls.wi));
            if (cosL <= 1e-8f) return std::nullopt;
            ls.pdf = dist2 / (cosL * area_);
        } else {
            // Cone sampling of the visible cap (pbrt-v4 §6.2.4): uniform in the subtended cone.
            const float dc = std::sqrt(dc2);
            const float sin2Max = radius_ * radius_ / dc2;
            const float cosMax = safeSqrt(1.0f - sin2Max);
            const Frame f = Frame::fromNormal(toC / dc);
            ls.wi = f.toWorld(sampleUniformCone(u, cosMax));
            // Nearest intersection of the ray with the sphere.
            const float b = glm::dot(ls.wi, toC);
            const float disc = b * b - (dc2 - radius_ * radius_);
            const float t = b - safeSqrt(disc);
            ls.pLight = p + t * ls.wi;
            const vec3 n = glm::normalize(ls.pLight - center_);
            ls.nLight = inward_ ? -n : n;
            ls.uv = sphereUV(glm::transpose(frame_) * n);
            ls.pdf = uniformConePdf(cosMax);
        }
    }
    at.p = ls.pLight;
    at.uv = ls.uv;
    ls.L = Le(at, ls.nLight, -ls.wi, wl);
    if (ls.L.isBlack()) return std::nullopt;
    return ls;
}

float AreaLight::pdfLi(const vec3& p, const vec3& wi, const SurfaceInteraction* hit) const {
    if (!hit) return 0.0f;
    if (kind_ == Kind::Sphere) {
        const vec3 toC = center_ - p;
        const float dc2 = glm::dot(toC, toC);
        if (dc2 > radius_ * radius_ * 1.00001f) return uniformConePdf(safeSqrt(1.0f - radius_ * radius_ / dc2));
    }
    const float cosL = std::abs(glm::dot(hit->ng, wi));
    if (cosL <= 1e-8f) return 0.0f;
    // The distance from p, not the hit's ray parameter: the ray that found the light may have
    // started at a pass-through surface between p and the light (integrators/volpath.cpp).
    const vec3 d = hit->p - p;
    return glm::dot(d, d) / (cosL * area_);
}

std::optional<LightEmission> AreaLight::sampleLe(const vec2& uPos, const vec2& uDir, const SampledWavelengths& wl,
                                                 const SceneBounds&) const {
    LightEmission e;
    if (kind_ == Kind::Sphere) {
        const vec3 n = sampleUniformSphere(uPos);
        e.at.p = center_ + radius_ * n;
        e.at.uv = sphereUV(glm::transpose(frame_) * n);
        e.n = inward_ ? -n : n;
    } else {
        sampleArea(uPos, e.at, e.n);
    }
    const vec3 local = sampleCosineHemisphere(uDir);
    const vec3 d = glm::normalize(Frame::fromNormal(e.n).toWorld(local));
    e.ray = Ray(offsetRayOrigin(e.at.p, e.n, d), d);  // off the surface: the ray must not find it again
    e.L = Le(e.at, e.n, e.ray.d, wl);
    if (e.L.isBlack()) return std::nullopt;
    e.pdfPos = 1.0f / area_;
    e.pdfDir = cosineHemispherePdf(local.z);
    if (!(e.pdfDir > 0)) return std::nullopt;
    return e;
}

vec2 AreaLight::pdfLe(const vec3&, const vec3& n, const vec3& w, const SceneBounds&) const {
    return vec2(1.0f / area_, cosineHemispherePdf(glm::dot(n, w)));
}

}  // namespace iris
