// The `gridvolume` volume (Mitsuba 3 src/volumes/grid.cpp): a voxel grid read from a .vol file
// (core/io/vol_reader.h) or, an iris extension, one grid of an OpenVDB .vdb file densified
// (core/io/vdb_reader.h: `filename` ending in .vdb and `grid`, the grid's name, optional when the
// file holds one grid). Parameters: filename; grid (.vdb only); filter_type (trilinear | nearest, default
// trilinear); wrap_mode (clamp | repeat | mirror, default clamp); to_world; raw (bool, default
// false); use_grid_bbox (bool, default false); accel (accepted, no effect: CUDA texture hardware).
//
// Conventions of Mitsuba 3, followed here:
//  - The grid fills the local unit cube [0,1]³ that to_world places in the world; the bounding box
//    written in the file is ignored unless use_grid_bbox is true, in which case the file's box is
//    mapped onto the unit cube first (grid.cpp: m_to_local = bbox_transform() · m_to_local;
//    include/mitsuba/render/volumegrid.h, bbox_transform = scale(1/(max−min)) · translate(−min)).
//  - Voxel (i, j, k) is the sample at the cell centre ((i+½)/xres, (j+½)/yres, (k+½)/zres):
//    trilinear lookups take x·res − ½, its floor and fraction (Dr.Jit include/drjit/texture.h,
//    Texture::eval_nonaccel, FilterMode::Linear); nearest lookups take floor(x·res)
//    (FilterMode::Nearest). Both neighbours of a trilinear lookup are wrapped by index.
//  - Wrap modes act on voxel indices (Dr.Jit Texture::wrap): clamp to [0, n−1]; repeat modulo n;
//    mirror with period 2n, the edge voxel repeated (…, 1, 0 | 0, 1, …, n−1 | n−1, …).
//  - 1-channel grids give the value in every lane; 3-channel grids are RGB. In RGB mode the
//    channels are returned as they are. In spectral mode each voxel's colour becomes a spectrum as
//    in Mitsuba 3 (grid.cpp, at load and in interpolate_spectral), whatever the parameter's kind:
//    scale = 2·max(rgb), the reflectance spectrum S of rgb/scale (a colour of maximum ½), and a
//    lookup is (Σ w_i S_i(λ)) · (Σ w_i scale_i) over the 8 trilinear corners (nearest: scale·S).
//    This is not the reflectance upsampling of the interpolated colour: both project onto the
//    same colour, but their shapes differ, and an albedo raised to the power of many scattering
//    events shows it (Mitsuba's hetero_sigmat_albedo test scene: X 0.985, Z 1.012 before). S comes
//    from RGBSpectrumGrid (spectral/rgb_spectrum_grid.h); the spectrum may exceed the colour's
//    maximum (an albedo above 1 at some wavelengths), as in Mitsuba 3.
//    raw = true makes Mitsuba 3's spectral variants refuse a 3-channel grid; iris upsamples it
//    anyway (raw has no effect in RGB mode in both).
//  - 6-channel grids hold the parameters of the sggx phase function (Mitsuba 3 src/phase/sggx.cpp,
//    Volume::eval_6); they are read raw through evalChannels, and a medium's spectrum parameters
//    refuse them (getVolume). Other channel counts are refused at load.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/io/vdb_reader.h"
#include "core/io/vol_reader.h"
#include "media/volumes/volume.h"
#include "spectral/rgb_spectrum_grid.h"

namespace iris {
namespace {

enum class Filter { Trilinear, Nearest };
constexpr int kMaxChannels = 6;  // 1 (scalar), 3 (RGB) or 6 (sggx's S)
enum class Wrap { Clamp, Repeat, Mirror };

Filter parseFilter(const Properties& p) {
    const std::string s = p.getString("filter_type", "trilinear");
    if (s == "trilinear") return Filter::Trilinear;
    if (s == "nearest") return Filter::Nearest;
    failAt(p.locationOf("filter_type"), "gridvolume: filter_type '", s, "' is not supported (supported: trilinear, nearest)");
}

Wrap parseWrap(const Properties& p) {
    const std::string s = p.getString("wrap_mode", "clamp");
    if (s == "clamp") return Wrap::Clamp;
    if (s == "repeat") return Wrap::Repeat;
    if (s == "mirror") return Wrap::Mirror;
    failAt(p.locationOf("wrap_mode"), "gridvolume: wrap_mode '", s, "' is not supported (supported: clamp, repeat, mirror)");
}

/// Index i wrapped into [0, n) (Dr.Jit Texture::wrap).
int64_t wrapIndex(int64_t i, int64_t n, Wrap w) {
    if (w == Wrap::Clamp) return std::clamp<int64_t>(i, 0, n - 1);
    if (w == Wrap::Repeat) return ((i % n) + n) % n;
    const int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);  // mirror: period 2n
    return m < n ? m : 2 * n - 1 - m;
}

/// floor(x) as an integer, x first limited to ±2^40 (points far outside the grid; every wrap
/// mode gives the same voxels for them as for any point that far).
int64_t floorIndex(float x) { return int64_t(std::floor(std::clamp(x, -1.0995116e12f, 1.0995116e12f))); }

class GridVolume final : public Volume {
public:
    GridVolume(VolumeGridData data, const mat4& toWorld, Filter filter, Wrap wrap)
        : Volume(toWorld), g_(std::move(data)), filter_(filter), wrap_(wrap) {
        range_.min = range_.max = g_.values.empty() ? 0.0f : g_.values[0];
        for (float v : g_.values) range_.min = std::min(range_.min, v), range_.max = std::max(range_.max, v);
        maxValue_ = laneBound(range_.max);
        if (g_.channels == 3) scaleColours();
    }

    SampledSpectrum eval(const vec3& p, const SampledWavelengths& wl) const override {
        const Corners k = corners(localPoint(p));
        if (g_.channels == 3 && !wl.isRGB()) return spectrum(k, wl);
        SampledSpectrum s(wl.size());
        for (int i = 0; i < k.count; ++i) {
            if (g_.channels == 1) s += SampledSpectrum(wl.size(), k.weight[i] * g_.values[k.voxel[i]]);
            else
                for (int c = 0; c < 3; ++c) s[c] += k.weight[i] * g_.values[k.voxel[i] * 3 + size_t(c)];
        }
        return s;
    }

    float maxValue() const override { return maxValue_; }

    float maxValueIn(const Box3& local) const override {
        const int res[3] = {g_.xres, g_.yres, g_.zres};
        std::vector<int> idx[3];
        for (int a = 0; a < 3; ++a) idx[a] = touchedIndices(local.lo[a], local.hi[a], res[a]);
        float m = -std::numeric_limits<float>::infinity();
        for (int z : idx[2])
            for (int y : idx[1])
                for (int x : idx[0])
                    for (int c = 0; c < g_.channels; ++c) m = std::max(m, g_.at(x, y, z, c));
        return laneBound(m);
    }

    ValueRange range() const override { return range_; }
    ivec3 resolution() const override { return ivec3(g_.xres, g_.yres, g_.zres); }
    int channels() const override { return g_.channels; }
    const VolumeGridData* grid() const override { return &g_; }
    void evalChannels(const vec3& p, float* c) const override {
        const Corners k = corners(localPoint(p));
        std::fill(c, c + g_.channels, 0.0f);
        for (int i = 0; i < k.count; ++i)
            for (int ch = 0; ch < g_.channels; ++ch) c[ch] += k.weight[i] * g_.values[k.voxel[i] * size_t(g_.channels) + size_t(ch)];
    }

private:
    /// The voxels a lookup blends (linear indices) and their weights.
    struct Corners {
        size_t voxel[8];
        float weight[8];
        int count = 0;
    };

    /// A bound over every lane of the values eval makes from colours whose channels are at most m:
    /// a scalar is m; RGB mode gives the channels; spectral mode Σ w S · Σ w scale ≤ 1 · 2m.
    float laneBound(float m) const { return g_.channels == 3 ? 2.0f * m : m; }

    /// Per voxel the colour rgb/scale and scale = 2·max(rgb) (Mitsuba 3 grid.cpp, the constructor's
    /// spectral conversion; 1e-8 keeps black voxels finite).
    void scaleColours() {
        const size_t n = g_.values.size() / 3;
        scaled_.resize(4 * n);
        for (size_t i = 0; i < n; ++i) {
            const float* rgb = &g_.values[3 * i];
            const float scale = 2.0f * std::max({rgb[0], rgb[1], rgb[2]});
            for (int c = 0; c < 3; ++c) scaled_[4 * i + c] = rgb[c] / std::max(1e-8f, scale);
            scaled_[4 * i + 3] = scale;
        }
    }

    /// The spectral value of a lookup: (Σ w_i S_i) · (Σ w_i scale_i) (Mitsuba 3 interpolate_spectral).
    SampledSpectrum spectrum(const Corners& k, const SampledWavelengths& wl) const {
        const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();
        SampledSpectrum shape(wl.size());
        float scale = 0.0f;
        for (int i = 0; i < k.count; ++i) {
            const float* v = &scaled_[4 * k.voxel[i]];
            shape += k.weight[i] * grid.reflectance(vec3(v[0], v[1], v[2]), wl);
            scale += k.weight[i] * v[3];
        }
        return shape * scale;
    }

    /// The wrapped voxel indices along one axis whose values influence a lookup at a local
    /// coordinate in [lo, hi] (both trilinear neighbours), each once.
    std::vector<int> touchedIndices(float lo, float hi, int n) const {
        const bool lin = filter_ == Filter::Trilinear;
        const int64_t i0 = floorIndex(lin ? lo * float(n) - 0.5f : lo * float(n));
        const int64_t i1 = floorIndex(lin ? hi * float(n) - 0.5f : hi * float(n)) + (lin ? 1 : 0);
        std::vector<char> hit(size_t(n), 0);
        if (wrap_ != Wrap::Clamp && i1 - i0 + 1 >= 2 * int64_t(n)) std::fill(hit.begin(), hit.end(), 1);
        else if (wrap_ == Wrap::Clamp) for (int64_t i = wrapIndex(i0, n, wrap_); i <= wrapIndex(i1, n, wrap_); ++i) hit[size_t(i)] = 1;
        else for (int64_t i = i0; i <= i1; ++i) hit[size_t(wrapIndex(i, n, wrap_))] = 1;
        std::vector<int> out;
        for (int i = 0; i < n; ++i)
            if (hit[size_t(i)]) out.push_back(i);
        return out;
    }

    /// The voxels a lookup at local point u blends, with the filter's weights.
    Corners corners(const vec3& u) const {
        Corners k;
        if (filter_ == Filter::Nearest) nearest(u, k);
        else trilinear(u, k);
        return k;
    }

    void nearest(const vec3& u, Corners& k) const {
        // FilterMode::Nearest: voxel floor(u·res) (Dr.Jit Texture::eval_nonaccel).
        const int x = int(wrapIndex(floorIndex(u.x * float(g_.xres)), g_.xres, wrap_));
        const int y = int(wrapIndex(floorIndex(u.y * float(g_.yres)), g_.yres, wrap_));
        const int z = int(wrapIndex(floorIndex(u.z * float(g_.zres)), g_.zres, wrap_));
        k.voxel[0] = g_.index(x, y, z, 0) / size_t(g_.channels);
        k.weight[0] = 1.0f;
        k.count = 1;
    }

    void trilinear(const vec3& u, Corners& k) const {
        // FilterMode::Linear: sample positions at cell centres, x·res − ½ (Dr.Jit eval_nonaccel).
        const int res[3] = {g_.xres, g_.yres, g_.zres};
        int i[3][2];
        float w[3][2];
        for (int a = 0; a < 3; ++a) {
            const float x = u[a] * float(res[a]) - 0.5f;
            const int64_t f = floorIndex(x);
            w[a][1] = std::clamp(x - float(f), 0.0f, 1.0f);
            w[a][0] = 1.0f - w[a][1];
            i[a][0] = int(wrapIndex(f, res[a], wrap_));
            i[a][1] = int(wrapIndex(f + 1, res[a], wrap_));
        }
        for (int corner = 0; corner < 8; ++corner) {
            const int bx = corner & 1, by = (corner >> 1) & 1, bz = corner >> 2;
            k.voxel[corner] = g_.index(i[0][bx], i[1][by], i[2][bz], 0) / size_t(g_.channels);
            k.weight[corner] = w[0][bx] * w[1][by] * w[2][bz];
        }
        k.count = 8;
    }

    VolumeGridData g_;
    Filter filter_;
    Wrap wrap_;
    std::vector<float> scaled_;  // 3-channel grids: per voxel rgb/scale and scale (scaleColours)
    ValueRange range_;
    float maxValue_ = 0.0f;
};

/// to_world · (the file's box → unit cube)⁻¹ when use_grid_bbox is set (Mitsuba 3 grid.cpp).
mat4 gridToWorld(const Properties& p, const mat4& toWorld, bool useGridBox, const VolumeGridData& g) {
    if (!useGridBox) return toWorld;
    const vec3 extent = g.bboxMax - g.bboxMin;
    if (!(extent.x > 0 && extent.y > 0 && extent.z > 0))
        failAt(p.locationOf("use_grid_bbox"), "gridvolume: use_grid_bbox needs a non-empty bounding box in the .vol file");
    return toWorld * glm::scale(glm::translate(mat4(1.0f), g.bboxMin), extent);
}

/// The file's grid: a .vol file, or the grid `grid` of a .vdb file; errors at the filename's line.
VolumeGridData readGridFile(const Properties& p, const std::string& file) {
    if (!isVdbFileName(file)) {
        if (p.present("grid")) failAt(p.locationOf("grid"), "gridvolume: 'grid' names a grid of a .vdb file; ", file, " is a .vol file");
        return withLocation(p.locationOf("filename"), [&] { return readVolFile(file); });
    }
    const std::string grid = p.getString("grid", "");
    return withLocation(p.locationOf("filename"), [&] { return readVdbFile(file, grid); });
}

std::shared_ptr<Volume> create(const Properties& p, SpectrumKind kind) {
    const std::string file = p.getString("filename");
    const Filter filter = parseFilter(p);
    const Wrap wrap = parseWrap(p);
    const mat4 toWorld = readToWorld(p);
    p.getBool("raw", false);   // see the file comment: no effect here
    p.getBool("accel", true);  // Mitsuba 3: CUDA hardware interpolation; no effect on the CPU
    const bool useGridBox = p.getBool("use_grid_bbox", false);
    if (kind == SpectrumKind::Illuminant) failAt(p.location(), "gridvolume: volumes cannot give emission spectra");
    VolumeGridData g = readGridFile(p, file);
    if (g.channels != 1 && g.channels != 3 && g.channels != kMaxChannels)
        failAt(p.locationOf("filename"), file, ": gridvolume supports grids of 1, 3 or 6 channels, this one has ", g.channels);
    const mat4 m = gridToWorld(p, toWorld, useGridBox, g);
    return std::make_shared<GridVolume>(std::move(g), m, filter, wrap);
}

}  // namespace

IRIS_REGISTER(VolumeRegistry, "gridvolume", create);

}  // namespace iris
