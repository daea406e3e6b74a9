// Volumes: spatially varying quantities of participating media (Mitsuba 3 `<volume>` plugins,
// include/mitsuba/render/volume.h, src/render/volume.cpp). A volume's local domain is the unit
// cube [0,1]³, placed in the world by `to_world` (Mitsuba 3 Volume: m_to_local =
// to_world⁻¹, and update_bbox() takes the world box as the box of the unit cube's 8 transformed
// corners). Outside [0,1]³ a grid's value follows its wrap mode. A volume evaluates, at a world
// point, to one value per wavelength lane of the path: a scalar grid gives the same value in every
// lane; an RGB grid gives its channels in RGB mode and an upsampled spectrum of the interpolated
// colour in spectral mode, of the SpectrumKind the parameter asks for (albedo: Reflectance,
// sigma_t: Unbounded). Each type registers a factory in VolumeRegistry under its scene-file name.
#pragma once

#include <memory>
#include <string>

#include "core/io/vol_reader.h"
#include "core/math.h"
#include "core/properties.h"
#include "core/ray.h"
#include "core/registry.h"
#include "spectral/spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {


/// An axis-aligned box [lo, hi] (world or local coordinates).
struct Box3 {
    vec3 lo{0.0f}, hi{0.0f};

    bool contains(const vec3& p) const {
        return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
    }
    bool degenerate() const { return !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z); }
    /// The piece [t0, t1] of the ray (any direction) over [0, tMax] inside the box (slab method,
    /// Kay & Kajiya 1986); false when it misses.
    bool clip(const Ray& ray, float tMax, float& t0, float& t1) const;
};

/// The box of the 8 corners of `b` mapped by the affine `m`: conservative for any affine map.
Box3 transformBox(const mat4& m, const Box3& b);

/// The smallest and largest value a volume stores (its data, before any RGB upsampling).
struct ValueRange {
    float min = 0.0f, max = 0.0f;
};

class Volume {
public:
    /// `toWorld` must be invertible (readToWorld checks it for scene files).
    explicit Volume(const mat4& toWorld);
    virtual ~Volume() = default;

    /// The value at the world point p for the path's wavelengths (wl.size() lanes).
    virtual SampledSpectrum eval(const vec3& p, const SampledWavelengths& wl) const = 0;
    /// An upper bound of eval over all points and every lane of any wavelengths.
    virtual float maxValue() const = 0;
    /// An upper bound of eval, every lane, at the points whose local coordinates lie in the box
    /// (any box of R³: outside the unit cube the wrap mode decides), for majorant grids.
    virtual float maxValueIn(const Box3& local) const { return (void)local, maxValue(); }
    /// The range of the stored values (an RGB grid: of its channels) for parameter checks.
    virtual ValueRange range() const = 0;
    /// Voxels per axis (1 for a constant volume).
    virtual ivec3 resolution() const { return ivec3(1); }
    /// True when eval is the same at every point (a constvolume).
    virtual bool isConstant() const { return false; }
    /// The number of raw channels evalChannels gives (a grid's channel count; 1 for a constvolume
    /// of a number, 3 for one of an <rgb>); 0 when there are none (a constvolume of a spectrum).
    virtual int channels() const { return 0; }
    /// The stored channels interpolated at the world point p, channels() floats, not upsampled
    /// (Mitsuba 3 Volume::eval_1 / eval_6: the phase functions' parameters).
    virtual void evalChannels(const vec3& p, float* out) const { (void)p, (void)out; }
    /// The voxels of a grid volume (for checks of every stored value), or nullptr.
    virtual const VolumeGridData* grid() const { return nullptr; }

    const mat4& toWorld() const { return toWorld_; }
    const mat4& toLocal() const { return toLocal_; }
    vec3 localPoint(const vec3& p) const { return transformPoint(toLocal_, p); }
    /// The world box of the unit cube (Mitsuba 3 Volume::update_bbox).
    const Box3& bounds() const { return bounds_; }

private:
    mat4 toWorld_, toLocal_;
    Box3 bounds_;
};

using VolumePtr = std::shared_ptr<const Volume>;
/// Every volume type, by its scene-file name (`<volume type="...">`), created for the spectrum
/// kind of the parameter it is given to.
using VolumeRegistry = Registry<Volume, SpectrumKind>;

/// `to_world` of a volume (default identity); a singular or non-finite matrix is an error at its line.
mat4 readToWorld(const Properties& p);

/// A constant volume with the given value (the `constvolume` plugin, and a number, <rgb> or
/// <spectrum> given where a volume is expected).
VolumePtr makeConstVolume(SpectrumPtr value, const mat4& toWorld = mat4(1.0f));

/// A volume-valued parameter (Mitsuba 3 Properties::volume): a nested <volume> (VolumeRegistry), or
/// any spectrum value (spectral/spectrum_params.h) as a constvolume; `def` when absent. A nested
/// volume of other than 1 or 3 channels (a 6-channel grid) is an error at its line.
VolumePtr getVolume(const Properties& p, const std::string& name, SpectrumKind kind, float def);

/// A float parameter that may vary in space (Mitsuba 3 Properties::volume read with eval_1): a
/// number, or a nested <volume> of one channel.
struct FloatVolume {
    float constant = 0.0f;
    VolumePtr volume;  // when set, the value at a point is its one channel there
    float eval(const vec3& p) const;
    /// The smallest and largest value it can take.
    ValueRange range() const;
};
FloatVolume getFloatVolume(const Properties& p, const std::string& name, float def);

/// A nested <volume> `name` (required) whose raw channels a phase function reads: exactly
/// `channels` of them (sggx's S: 6), else an error at its line.
VolumePtr getChannelVolume(const Properties& p, const std::string& name, int channels);

}  // namespace iris
