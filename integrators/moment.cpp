// Mitsuba 3's "moment" integrator: renders with the one nested integrator and asks for the
// per-pixel first and second moments of the samples as extra image channels. The film keeps
// per-pixel sums of values and of squared values anyway (render/film.h), so this wrapper only
// delegates (also the splats of a light-tracing integrator: the film's samples are then the
// passes' sums, render/splat_film.h); apps/render writes the channels moment1.* and moment2.* (in the film's space) when
// the scene's integrator is a moment integrator.
#include "render/integrator.h"

namespace iris {

namespace {

class MomentIntegrator final : public Integrator {
public:
    explicit MomentIntegrator(IntegratorPtr nested) : Integrator("moment", nested->maxDepth()), nested_(std::move(nested)) {}
    SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override {
        return nested_->Li(scene, ray, wl, sampler, arena, stats);
    }
    bool rendersMedia() const override { return nested_->rendersMedia(); }
    bool splats() const override { return nested_->splats(); }
    SampledSpectrum sample(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                           PathStats& stats, SplatFilm& splats) const override {
        return nested_->sample(scene, ray, wl, sampler, arena, stats, splats);
    }
    bool hasPolarizedForm() const override { return nested_->hasPolarizedForm(); }
    void LiStokes(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  StokesEstimate& est) const override {
        nested_->LiStokes(scene, ray, wl, sampler, arena, stats, est);
    }

private:
    IntegratorPtr nested_;
};

std::shared_ptr<Integrator> createMoment(const Properties& p) {
    PropertiesPtr nested;
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "integrator") failAt(c->location(), "unexpected <", c->tag(), "> inside <integrator type=\"moment\">");
        if (nested) failAt(c->location(), "iris's moment integrator takes exactly one nested integrator");
        nested = c;
    }
    if (!nested) failAt(p.location(), "the moment integrator needs a nested <integrator> (e.g. <integrator type=\"path\"/>)");
    if (nested->type() == "moment") failAt(nested->location(), "a moment integrator cannot nest another one");
    return std::make_shared<MomentIntegrator>(IntegratorRegistry::instance().create(*nested));
}

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "moment", createMoment);

}  // namespace iris
