#include "render/integrator.h"

#include "core/error.h"

namespace iris {

IntegratorPtr makeIntegrator(const std::string& type) {
    return IntegratorRegistry::instance().create(Properties("integrator", type, {}));
}

void Integrator::LiStokes(const Scene&, const Ray&, SampledWavelengths&, Sampler&, Arena&, PathStats&, StokesEstimate&) const {
    fail("the ", type_, " integrator has no polarized form (docs/polarization.md)");
}

}  // namespace iris
