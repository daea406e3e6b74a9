#include "integrators/bdpt.h"

#include <cstdio>
#include <vector>

#include "core/error.h"
#include "integrators/bdpt_connect.h"
#include "integrators/bdpt_walk.h"
#include "render/splat_film.h"

namespace iris {

namespace {
/// Subpaths of an unlimited max_depth stop at this many vertices (Russian roulette ends them long
/// before in any scene that absorbs light).
constexpr int kMaxVertices = 256;
}  // namespace

BDPTIntegrator::BDPTIntegrator(const BDPTParams& params)
    : Integrator("bdpt", params.path.maxDepth), params_(params),
      maxSegments_(params.path.maxDepth < 0 ? kMaxVertices - 1 : std::min(params.path.maxDepth, kMaxVertices - 1)) {}

SampledSpectrum BDPTIntegrator::Li(const Scene&, const Ray&, SampledWavelengths&, Sampler&, Arena&, PathStats&) const {
    fail("the bdpt integrator splats its light-subpath connections on the film: it renders through the renderer, not per camera ray");
}

bool BDPTIntegrator::evaluated(int s, int t) const {
    const int segments = s + t - 1;
    if (segments < 1 || segments > maxSegments_ || (s == 1 && t == 1)) return false;
    if (t == 1 && !params_.strategies.lightImage) return false;
    if (s == 1 && !params_.strategies.sampleDirect) return false;
    return !(params_.path.hideEmitters && segments == 1);
}

SampledSpectrum BDPTIntegrator::sample(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                       PathStats& stats, SplatFilm& splats) const {
    if (!scene.description().camera.sensor->pinhole())
        fail("bdpt needs a perspective sensor: an orthographic one has a delta direction, which BDPT's multiple importance "
             "sampling does not handle (pbrt-v4 neither); use ptracer or path");
    ++stats.paths;
    thread_local std::vector<BDPTVertex> cameraPath, lightPath;
    cameraPath.resize(size_t(maxSegments_ + 1));
    lightPath.resize(size_t(maxSegments_));
    const WalkParams walk{params_.path.rrDepth, params_.path.strictNormals};
    const int nCamera = cameraSubpath(scene, ray, wl, sampler, arena, stats, walk, cameraPath.data(), maxSegments_ + 1);
    const int nLight = lightSubpath(scene, wl, sampler, arena, stats, walk, lightPath.data(), maxSegments_);
    SampledSpectrum L(wl.size());
    for (int t = 1; t <= nCamera; ++t)
        for (int s = 0; s <= nLight; ++s) {
            if (!evaluated(s, t)) continue;
            const std::optional<BDPTConnection> c =
                connectStrategy(scene, lightPath.data(), cameraPath.data(), s, t, wl, sampler, params_.path.strictNormals, stats);
            if (!c || c->L.isBlack() || !kept(s, t)) continue;
            const float w = params_.misWeights && !noMIS_ ? misWeight(scene, lightPath.data(), cameraPath.data(), c->sampled, s, t,
                                                           params_.heuristic, params_.strategies)
                                               : 1.0f;
            if (t == 1)
                splats.splat(*c->filmPos, c->L * w, wl);
            else
                L += c->L * w;
        }
    return L;
}

BDPTParams readBDPTParams(const Properties& p) {
    BDPTParams b;
    const std::string mis = p.getString("mis", "power");
    if (mis == "balance") b.heuristic = MISHeuristic::Balance;
    else if (mis != "power") failAt(p.locationOf("mis"), "mis must be 'power' or 'balance', got '", mis, "'");
    b.strategies.lightImage = p.getBool("light_image", true);
    b.strategies.sampleDirect = p.getBool("sample_direct", true);
    b.misWeights = p.getBool("mis_weights", true);
    if (p.has("strategy")) {
        const std::string st = p.getString("strategy");
        int s = -1, t = -1;
        char tail = 0;
        if (std::sscanf(st.c_str(), "%d,%d%c", &s, &t, &tail) != 2 || s < 0 || t < 1 || (s == 1 && t == 1))
            failAt(p.locationOf("strategy"), "strategy must be 's,t' with s >= 0, t >= 1 and not 1,1 (e.g. '0,3'), got '", st, "'");
        b.onlyS = s;
        b.onlyT = t;
    } else if (!b.misWeights) {
        failAt(p.locationOf("mis_weights"), "mis_weights = false needs a 'strategy' (an unweighted split estimates its whole path length)");
    }
    b.path = readPathParams(p);
    return b;
}

namespace {

std::shared_ptr<Integrator> createBDPT(const Properties& p) { return std::make_shared<BDPTIntegrator>(readBDPTParams(p)); }

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "bdpt", createBDPT);

}  // namespace iris
