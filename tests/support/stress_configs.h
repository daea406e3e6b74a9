// Stress configurations for every registered material (used by test_stress_materials.cpp).
//
// Each material name maps to a list of parameter sets that push the material to its extremes
// (roughness 1e-4 … 1 and the smooth variant, η from 1.0001 to 4 and below 1, k up to 10, film
// thickness 0 … 1e5 nm, per-channel values, tilted normals …) and to an energy expectation:
// energy-conserving materials must have a directional albedo ≤ 1 (within the estimator's noise);
// the others (by design: the thesis' phase term, Disney sheen/retro-reflection, cloth sheen) are
// measured and only bounded generously. A registered material without an entry here makes the
// stress test fail with a message asking for one (docs/numerics.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/properties.h"

namespace iris::stress {

struct StressCase {
    std::string label;           // short description printed in failure messages and reports
    PropertiesPtr props;         // tag "bsdf", ready for MaterialRegistry::create
    // A measured, documented energy defect of an energy-conserving material (docs/numerics.md,
    // "Known energy defects"): where |cosθo| < knownBelowCos the albedo is only required to stay
    // below knownAlbedoLimit (still finite, still ≥ 0). knownAlbedoLimit = 0: no known defect.
    double knownAlbedoLimit = 0;
    float knownBelowCos = 2.0f;
    std::string knownIssue;
};

struct MaterialStress {
    bool known = false;          // false: no configuration for this material (the test fails)
    bool conservesEnergy = true; // assert albedo ≤ 1 + noise; otherwise report the excess only
    double generousBound = 1.0;  // for non-conserving materials: albedo must stay below this
    std::string note;            // why a material does not conserve energy (for the report)
    // A measured, documented defect: sample() f/pdf differ from eval/pdf(wo, wi) by more than 1 %
    // somewhere; consistency is then only reported (STRESS-CONSISTENCY), not asserted.
    std::string consistencyKnownIssue;
    std::vector<StressCase> cases;
};

/// The stress configurations of the material registered as `name` (known = false when none).
MaterialStress stressConfigsFor(const std::string& name);

/// Every material name that has configurations (to detect stale entries).
std::vector<std::string> stressConfiguredNames();

}  // namespace iris::stress
