// Rays per second of the full renderer versus bare Embree traversal of the same kind of rays
// (primary rays plus one cosine-distributed diffuse bounce from each primary hit), on the default
// scene and on any scene given with --scene=FILE. The ratio renderer/bare is the shading overhead.
//   build/bench_render [--scene=path.xml] [--benchmark_filter=...]
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/source_tree.h"
#include "render/scene.h"

using namespace iris;

namespace {

std::string gScenePath = iris::sourcePath("scenes/default.xml");

const Scene& scene() {
    static std::unique_ptr<Scene> s = [] {
        SceneDescription d = loadScene(gScenePath, {{"res", "128"}});
        return std::make_unique<Scene>(std::move(d));
    }();
    return *s;
}

/// Primary rays through every pixel centre plus one diffuse bounce ray from each hit.
const std::vector<Ray>& rayBatch() {
    static std::vector<Ray> rays = [] {
        std::vector<Ray> out;
        const Scene& sc = scene();
        const CameraDescription& cam = sc.description().camera;
        Sampler sampler(1234);
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const Ray r = cam.sensor->generateRay(vec2(x + sampler.get1D(), y + sampler.get1D()));
                out.push_back(r);
                if (const auto hit = sc.intersect(r)) {
                    const Frame f = Frame::fromNormal(glm::dot(hit->ng, r.d) < 0 ? hit->ng : -hit->ng);
                    out.push_back(hit->spawnRay(f.toWorld(sampleCosineHemisphere(sampler.get2D()))));
                }
            }
        return out;
    }();
    return rays;
}

void BM_BareEmbreeClosestHit(benchmark::State& state) {
    const std::vector<Ray>& rays = rayBatch();
    RTCScene rtc = static_cast<RTCScene>(scene().embreeScene());
    uint64_t traced = 0, hits = 0;
    for (auto _ : state) {
        for (const Ray& r : rays) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            RTCRayHit rh;
            rh.ray.org_x = r.o.x; rh.ray.org_y = r.o.y; rh.ray.org_z = r.o.z;
            rh.ray.dir_x = r.d.x; rh.ray.dir_y = r.d.y; rh.ray.dir_z = r.d.z;
            rh.ray.tnear = 0; rh.ray.tfar = r.tMax; rh.ray.mask = ~0u; rh.ray.flags = 0; rh.ray.time = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(rtc, &ctx, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        traced += rays.size();
    }
    benchmark::DoNotOptimize(hits);
    state.counters["rays/s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
}

void BM_RendererPathTracing(benchmark::State& state) {
    const Scene& sc = scene();
    RenderOptions opt;
    opt.threads = 1;  // compare with the single-threaded bare traversal above
    opt.spp = 1;
    opt.rgbMode = state.range(0) == 0;
    opt.spectralSamples = opt.rgbMode ? 3 : int(state.range(0));
    uint64_t rays = 0;
    for (auto _ : state) {
        Film film(sc.description().camera.width, sc.description().camera.height);
        const RenderStats st = Renderer(sc, opt).render(film);
        rays += st.rays;
    }
    state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
    state.SetLabel(opt.rgbMode ? "rgb" : "spectral N=" + std::to_string(opt.spectralSamples));
}

}  // namespace

BENCHMARK(BM_BareEmbreeClosestHit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RendererPathTracing)->Arg(0)->Arg(4)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i)
        if (std::strncmp(argv[i], "--scene=", 8) == 0) gScenePath = argv[i] + 8;
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
