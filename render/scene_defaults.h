// What a scene gets where its file names nothing, written once (Mitsuba 3's defaults): the
// integrator of a scene without <integrator>, the reconstruction filter of a film without
// <rfilter> (a Gaussian of standard deviation 0.5 px), and the material of a shape without <bsdf>
// (diffuse, reflectance 0.5). The loaders fill these in; the renderer and the metadata writer fall
// back to the same names for scene descriptions built in code.
#pragma once

namespace iris {

inline constexpr const char* kDefaultIntegrator = "path";
inline constexpr const char* kDefaultFilter = "gaussian";
inline constexpr const char* kDefaultMaterial = "diffuse";

}  // namespace iris
