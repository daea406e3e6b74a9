#include "integrators/segment_transmittance.h"

#include "integrators/transport_steps.h"

namespace iris {

std::optional<std::pair<SampledSpectrum, int>> segmentTransmittance(const Scene& scene, const vec3& p, const vec3& ng, const vec3& q,
                                                                     const SampledWavelengths& wl, bool passThrough, Arena& arena,
                                                                     PathStats& stats) {
    vec3 d = q - p;
    vec3 o = glm::dot(ng, ng) > 0 ? offsetRayOrigin(p, ng, d) : p;
    SampledSpectrum T(wl.size(), 1.0f);
    for (int crossings = 0; crossings < 1000; ++crossings) {
        ++stats.rays;
        d = q - o;
        if (!passThrough) {
            if (scene.occluded(Ray(o, d, 1.0f - 1e-4f))) return std::nullopt;
            return std::make_pair(T, 0);
        }
        const std::optional<SurfaceInteraction> hit = scene.intersect(Ray(o, d, 1.0f - 1e-4f));
        if (!hit) return std::make_pair(T, crossings);
        const std::optional<SampledSpectrum> w = crossingWeight(*hit, glm::normalize(d), wl, arena);
        if (!w || w->isBlack()) return std::nullopt;
        T *= *w;
        o = hit->spawnRay(d).o;
    }
    return std::nullopt;
}

}  // namespace iris
