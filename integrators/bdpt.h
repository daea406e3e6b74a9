// Bidirectional path tracing (`bdpt`; Veach 1997 ch. 10; Mitsuba 0.6 src/integrators/bdpt;
// pbrt-v4 §13.x): one camera subpath and one light subpath per pixel sample, every split (s, t) of
// every path length connected and weighted by multiple importance sampling (power or balance
// heuristic, integrators/bdpt_mis.h). The t = 1 strategies (light-subpath vertices seen by the
// camera) land anywhere on the film and are splatted (render/splat_film.h), so bdpt renders, resumes
// and splits as ptracer does. Spectral: both subpaths carry the sample's wavelengths (hero sampling,
// Wilkie et al. 2014: the MIS weights are those of the hero's densities, which are every lane's, as
// directions do not depend on the wavelength; a dispersive refraction ends the secondary lanes of
// the whole sample). Surfaces only: scenes with participating media are refused (as by `path`).
//
// Parameters (Mitsuba 0.6 bdpt and pbrt-v4 bdpt): max_depth (−1, path segments as `path`; pbrt's
// maxdepth counts bounces, one less), rr_depth (5), hide_emitters, strict_normals, light_image
// (true: the t = 1 strategies), sample_direct (true: the s = 1 strategies), mis ("power", Mitsuba
// 0.6; or "balance", pbrt-v4). For checking the estimator (pbrt-v4's visualizestrategies and
// visualizeweights): strategy ("s,t": only that split's contribution is kept; the images of all
// splits sum to the image) and mis_weights (false: that split unweighted, an estimate of the whole
// of its path length by itself).
#pragma once

#include "integrators/bdpt_mis.h"
#include "integrators/path.h"

namespace iris {

struct BDPTParams {
    PathParams path;
    MISHeuristic heuristic = MISHeuristic::Power;
    StrategySet strategies;
    int onlyS = -1, onlyT = -1;  // strategy "s,t" (−1: all)
    bool misWeights = true;
};

BDPTParams readBDPTParams(const Properties& p);

class BDPTIntegrator final : public Integrator {
public:
    explicit BDPTIntegrator(const BDPTParams& params);
    SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override;
    bool splats() const override { return true; }
    SampledSpectrum sample(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                           PathStats& stats, SplatFilm& splats) const override;
    const BDPTParams& params() const { return params_; }
    /// For tests only: every strategy at full weight (a deliberately wrong, over-counting estimator).
    void disableMIS() { noMIS_ = true; }

private:
    /// Strategy (s, t) is evaluated at all (its own switch, the depth limit, hide_emitters).
    bool evaluated(int s, int t) const;
    /// Its contribution is kept (the strategy option).
    bool kept(int s, int t) const { return params_.onlyS < 0 || (s == params_.onlyS && t == params_.onlyT); }

    BDPTParams params_;
    int maxSegments_;
    bool noMIS_ = false;
};

}  // namespace iris
