// The two principled models of iris (docs/materials_principled_cloth.md):
//   * Disney 2012 (Burley's BRDF, materials/principled.cpp): plugin `disney`, which a version 0.x
//     scene's `principled` becomes in the upgrade pass (render/loader/scene_upgrade.h; Mitsuba 0.6
//     has no principled plugin; iris's `principled` was this model before Mitsuba 3's was added);
//   * Mitsuba 3's `principled` BSDF and `principledthin` (materials/principled_mitsuba.cpp).
#pragma once

#include <memory>

#include "core/properties.h"
#include "materials/material.h"

namespace iris {

/// The Disney 2012 model from its scene parameters (materials/principled.cpp).
std::shared_ptr<Material> createDisneyPrincipled(const Properties& p);

}  // namespace iris
