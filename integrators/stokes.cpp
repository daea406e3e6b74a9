// Mitsuba 3's "stokes" integrator (src/integrators/stokes.cpp): renders with its one nested
// integrator in polarized mode and measures the whole Stokes vector S0..S3 of the light reaching
// the camera, in the camera's reference basis x = ray direction × the sensor's up vector (world
// space), the basis Mitsuba rotates the nested estimate to. The image is S0; apps/render writes
// S0..S3 as extra channels (docs/polarization.md). Polarized mode only, as in Mitsuba ("This
// integrator should only be used in polarized mode!"; render/renderer.cpp refuses it otherwise).
#include "core/error.h"
#include "render/integrator.h"

namespace iris {

namespace {

class StokesIntegrator final : public Integrator {
public:
    explicit StokesIntegrator(IntegratorPtr nested) : Integrator("stokes", nested->maxDepth()), nested_(std::move(nested)) {}
    SampledSpectrum Li(const Scene&, const Ray&, SampledWavelengths&, Sampler&, Arena&, PathStats&) const override {
        fail("the stokes integrator needs polarized mode (render --mode polarized)");
    }
    bool rendersMedia() const override { return nested_->rendersMedia(); }
    bool hasPolarizedForm() const override { return nested_->hasPolarizedForm(); }
    void LiStokes(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  StokesEstimate& est) const override {
        const vec3 up = glm::normalize(mat3(scene.description().camera.sensor->toWorld()) * vec3(0, 1, 0));
        const vec3 d = glm::normalize(ray.d);
        est.rows = 4;
        est.basis = glm::normalize(glm::cross(d, up));  // Mitsuba 3 stokes.cpp: cross(ray.d, vertical)
        nested_->LiStokes(scene, ray, wl, sampler, arena, stats, est);
    }

private:
    IntegratorPtr nested_;
};

std::shared_ptr<Integrator> createStokes(const Properties& p) {
    PropertiesPtr nested;
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "integrator") failAt(c->location(), "unexpected <", c->tag(), "> inside <integrator type=\"stokes\">");
        if (nested) failAt(c->location(), "the stokes integrator takes exactly one nested integrator (Mitsuba: \"More than one sub-integrator specified!\")");
        nested = c;
    }
    if (!nested) failAt(p.location(), "the stokes integrator needs a nested <integrator> (e.g. <integrator type=\"path\"/>)");
    if (nested->type() == "stokes") failAt(nested->location(), "a stokes integrator cannot nest another one");
    return std::make_shared<StokesIntegrator>(IntegratorRegistry::instance().create(*nested));
}

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "stokes", createStokes);

}  // namespace iris
