#include "render/integrator.h"

namespace iris {

IntegratorPtr makeIntegrator(const std::string& type) {
    return IntegratorRegistry::instance().create(Properties("integrator", type, {}));
}

}  // namespace iris
