// What a scene gets where its file names nothing, written once (Mitsuba 3's defaults unless said
// otherwise): the integrator of a scene without <integrator>, the sensor of a scene without
// <sensor>, a sensor's film and sampler, a film's reconstruction filter (a Gaussian of standard
// deviation 0.5 px), and the material of a shape without <bsdf> (diffuse, reflectance 0.5). The
// upgrade pass (render/loader/scene_upgrade.h) writes them into a parsed scene; the renderer, the
// metadata writer and the Python module fall back to the same names for scenes built in code.
#pragma once

namespace iris {

inline constexpr const char* kDefaultIntegrator = "path";
inline constexpr const char* kDefaultSensor = "perspective";
inline constexpr const char* kDefaultFilm = "hdrfilm";
inline constexpr const char* kDefaultSampler = "independent";
/// The sample count of a sensor without <sampler>. iris's own rule (kept from its first loader):
/// Mitsuba 3's default sampler draws 4 samples per pixel, its independent sampler's default
/// sample_count (render/samplers/samplers.cpp), but a scene without a sampler renders 16.
inline constexpr int kDefaultSampleCount = 16;
inline constexpr const char* kDefaultFilter = "gaussian";
inline constexpr const char* kDefaultMaterial = "diffuse";

}  // namespace iris
