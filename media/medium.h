// The participating-medium interface (Mitsuba 3 `<medium>` plugins; the null-scattering
// formulation of Miller, Georgiev & Jarosz 2019 as pbrt-v4 §11.4 and §14.2 present it).
//
// A medium gives, per wavelength lane, the scattering and extinction coefficients σ_s and σ_t
// (1/scene units) at a point, and along a ray a sequence of segments with a majorant σ_maj ≥ σ_t
// (every lane) over each: free-flight distances are sampled against σ_maj and the difference
// σ_n = σ_maj − σ_t is null scattering (delta and ratio tracking). A homogeneous medium has one
// segment with σ_maj = σ_t (no null collisions); a grid medium one per majorant-grid cell.
// Absorption is σ_a = σ_t − σ_s; albedo = σ_s/σ_t. A medium may emit: Mitsuba 3's `volumelight`
// (nested in the <medium>, or attached to a shape whose interior it is) gives an emission volume j
// (media/volume_light.h).
// Each type registers a factory in MediumRegistry under its scene-file name.
#pragma once

#include <memory>
#include <optional>

#include "core/arena.h"
#include "core/properties.h"
#include "core/ray.h"
#include "core/registry.h"
#include "media/phase/phase_function.h"
#include "media/volumes/volume.h"
#include "spectral/spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

/// σ_s and σ_t at a point, per lane (1/scene units).
struct MediumCoefficients {
    SampledSpectrum sigmaS, sigmaT;
};

/// A piece [tMin, tMax) of a ray (t in scene units along a unit direction) over which sigmaMaj
/// bounds σ_t in every lane.
struct MajorantSegment {
    float tMin = 0.0f, tMax = 0.0f;
    SampledSpectrum sigmaMaj;
};

/// The majorant segments of one ray, in increasing t. Lives in the per-thread Arena.
class MajorantIterator {
public:
    /// The next segment, or nullopt after the last one.
    virtual std::optional<MajorantSegment> next() = 0;

protected:
    ~MajorantIterator() = default;  // arena objects are never destroyed
};

class Medium {
public:
    Medium(PhaseFunctionPtr phase, bool sampleEmitters, VolumePtr emission = nullptr)
        : phase_(std::move(phase)), sampleEmitters_(sampleEmitters), emission_(std::move(emission)) {}
    virtual ~Medium() = default;

    /// σ_s and σ_t at the world point p for the path's wavelengths.
    virtual MediumCoefficients coefficients(const vec3& p, const SampledWavelengths& wl) const = 0;
    /// The majorant segments of the ray (its direction must be a unit vector) over [0, tMax).
    /// Segments may leave gaps where the medium is empty (σ_t = 0 there).
    virtual MajorantIterator* majorants(const Ray& ray, float tMax, const SampledWavelengths& wl, Arena& arena) const = 0;

    const PhaseFunction& phase() const { return *phase_; }
    /// Mitsuba's sample_emitters: next-event estimation from points inside the medium.
    bool sampleEmitters() const { return sampleEmitters_; }
    /// The emitted radiance per unit length j(p) of a volumelight (media/volume_light.h), or nullptr.
    const Volume* emission() const { return emission_.get(); }
    /// Attaches a volumelight while the scene loads (a shape's <emitter type="volumelight"> with this
    /// medium inside it, Mitsuba 3 Medium::set_emitter); an error at `where` if it has one already.
    void setEmission(VolumePtr emission, const SourceLocation& where);

private:
    PhaseFunctionPtr phase_;
    bool sampleEmitters_;
    VolumePtr emission_;
};

using MediumPtr = std::shared_ptr<const Medium>;
/// Every medium type, by its scene-file name (`<medium type="...">`).
using MediumRegistry = Registry<Medium>;

/// The parameters every medium has (Mitsuba 3, src/render/medium.cpp): its nested `<phase>` (at
/// most one, named or not; default isotropic) and `sample_emitters` (default true).
struct MediumCommon {
    PhaseFunctionPtr phase;
    bool sampleEmitters = true;
    VolumePtr emission;  // a nested <emitter type="volumelight">
};
/// Reads MediumCommon; any other nested object is an error naming its line.
MediumCommon readMediumCommon(const Properties& p);

/// A single segment [0, tMax) with a constant majorant: homogeneous media, and a constant bound.
class ConstantMajorantIterator final : public MajorantIterator {
public:
    ConstantMajorantIterator(float tMin, float tMax, const SampledSpectrum& sigmaMaj) : seg_{tMin, tMax, sigmaMaj} {}
    std::optional<MajorantSegment> next() override {
        if (done_ || !(seg_.tMax > seg_.tMin)) return std::nullopt;
        done_ = true;
        return seg_;
    }

private:
    MajorantSegment seg_;
    bool done_ = false;
};

}  // namespace iris

namespace iris {

/// A medium's spectrum parameter `name` must lie in [lo, hi] at every wavelength (checked in RGB
/// mode and at 32 wavelengths over [360, 830] nm); the error names its line and the value found.
void checkMediumSpectrum(const Properties& p, const std::string& name, const Spectrum& s, float lo, float hi);

}  // namespace iris
