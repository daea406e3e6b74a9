#include "render/filters/rfilter.h"

namespace iris {

ReconstructionFilterPtr makeFilter(const std::string& type) {
    return RFilterRegistry::instance().create(Properties("rfilter", type, {}));
}

}  // namespace iris
