// Latitude-longitude HDR environment map (Mitsuba "envmap"). Direction convention (Mitsuba): in
// the light's frame, θ is measured from +y, φ = atan2(x, −z); u = φ/2π, v = θ/π.
//
// Radiance is interpolated bilinearly between texels placed as `convention` says
// (render/lights/envmap_lattice.h; core/mitsuba_convention.h: "mitsuba3" by default, "mitsuba0.6"
// in a version 0.x file, written by the upgrade pass).
// Directions are importance sampled from a piecewise-constant density over a grid of cells in
// (u, v) (pbrt-v4 §12.5.2), each weighted by the exact cell average of the interpolated luminance
// × sinθ at the cell centre: a cell whose average is zero has zero radiance everywhere (the
// interpolant is non-negative), and a small floor keeps every direction samplable, so sampleLi and
// pdfLi are one density and the estimator stays unbiased with MIS.
//
// Spectral mode: texel RGB (linear Rec.709) becomes an illuminant spectrum. Solving the
// RGB→spectrum fit per texel would cost seconds, so the map's chromaticities c = rgb/max(rgb)
// are located in a 17³ grid whose corner spectra are fitted lazily (only corners the map uses,
// once, on the first spectral lookup) and interpolated trilinearly. Because the RGB projection is
// linear in the spectrum, the interpolated spectrum still projects exactly to the texel's RGB
// (up to the corners' own fitting error). Between texels, spectra are interpolated as the
// convention's Mitsuba does (see lookup()).
//
// Cost (issue 37): every texel's scale, cell corners and corner weights are computed once, with
// the grid (EnvmapTexelShape); so is, per 2×2 texel block, the merged list of the at most 16 corner
// nodes of its four texels (EnvmapNodeBlocks, render/lights/envmap_node_blocks.h: first-appearance
// order, each texel's corner weight per node, about 130 bytes per texel, capped at
// kMaxBlockBytes), so that a lookup's node weights are four products and three sums per four nodes
// in the general merge's order (bit-identical). Where that does not apply (a pole row, a black
// texel, a block past the cap, a contribution that underflows) the lookup merges node by node,
// taking a node that several texels share once with the sum of its weights. Each node's sigmoid
// is evaluated for all wavelengths in SIMD lanes, two nodes per AVX2 instruction for N ≤ 4. Next-
// event estimation takes the sample without its radiance (sampleLiDeferred) and looks it up
// (deferredRadiance) only where the BSDF is not black and the shadow ray unoccluded
// (integrators/transport_steps.h, RadianceLookup): 1.79 → 1.45 lookups per camera sample.
// Bunny scene (experiments/perf/scenes/bunny.xml), N = 4, instructions per lookup with the kernel
// (callgrind, inclusive cost of lookup and its call count, `render experiments/perf/scenes/bunny.xml
// -D res=64 --spp 66` minus `--spp 2`, --threads 1 --seed 1): 3890 → 880 (per-texel shapes and the
// SIMD kernel) → 602 (block node lists; 15 of the 392 944 lookups of the 66-spp run take the general
// merge). The block lists add about 176 M instructions, once, to the grid's construction on the
// first spectral lookup.
#include <atomic>
#include <cstdint>
#include <cstring>
#include <mutex>

#include "core/io/image.h"
#include "render/lights/envmap_lattice.h"
#include "render/lights/envmap_node_blocks.h"
#include "render/lights/light.h"
#include "core/registry.h"
#include "core/sampling.h"
#include "spectral/lane_dispatch.h"
#include "spectral/rgb_spectrum.h"

namespace iris {
namespace {

constexpr int kGrid = 17;
// Memory cap of the per-block node lists (EnvmapNodeBlocks; blocks beyond it merge in general):
// about 130 bytes per texel, 17 MB for the 512×256 museum map.
constexpr size_t kMaxBlockBytes = size_t(32) << 20;

/// A grid node's illuminant shape, RGBSpectrum::shapeValue = scale · (grey ? level : S(poly)).
struct GridNode {
    float c0 = 0, c1 = 0, c2 = 0;  // the sigmoid polynomial (SigmoidPolynomial)
    float scale = 0;
    float greyValue = 0;           // scale · level for a grey node
    bool grey = false;
};

constexpr float kSigmoidClamp = 9.223372036854775808e18f;  // SigmoidPolynomial::sigmoid's clamp, 2^63

// acc += Σ_e w_e · shape_e(λ) over the nodes nodes[nodeOf[e]], e < count, in that order, at the
// `padded` lanes of normalised wavelengths tl (SigmoidPolynomial::normalisedWavelength). Every node
// is an Illuminant RGBSpectrum, eval = shape(λ) · k · D65(λ) with the same k, so the weighted sum of
// the shapes is taken first and k · D65(λ) applied once (linearity; the result differs from summing
// the nodes' eval only by float rounding). Each shape value is RGBSpectrum::shapeValue's operations
// in its order, lane by lane (spectral/lanes.h: the same values as the scalar form); the sigmoid's
// clamp at ±2^63 is left out where no node's polynomial can reach it (clampFree). Two builds that
// give the same bits: the baseline one four wavelengths per instruction, the AVX2 one eight (for
// N ≤ 4, two nodes per instruction; the sum still adds node by node in order).
void addNodeShapesBaseline(const GridNode* nodes, const uint16_t* nodeOf, const float* weightOf, int count, const float* tl,
                           int padded, bool clampFree, float* acc) {
    using lanes::Float4;
    for (int e = 0; e < count; ++e) {
        const GridNode& node = nodes[nodeOf[e]];
        const float w = weightOf[e];
        if (node.grey) {
            const Float4 v = lanes::broadcast(w * node.greyValue);
            for (int i = 0; i < padded; i += 4) lanes::store(acc + i, lanes::load(acc + i) + v);
            continue;
        }
        const Float4 c0 = lanes::broadcast(node.c0), c1 = lanes::broadcast(node.c1), c2 = lanes::broadcast(node.c2);
        const Float4 nodeScale = lanes::broadcast(node.scale), wv = lanes::broadcast(w);
        for (int i = 0; i < padded; i += 4) {
            const Float4 t = lanes::load(tl + i);
            Float4 x = (c0 * t + c1) * t + c2;
            if (!clampFree) x = lanes::clamp(x, lanes::broadcast(-kSigmoidClamp), lanes::broadcast(kSigmoidClamp));
            const Float4 sig = 0.5f + x / (2.0f * lanes::sqrt(1.0f + x * x));
            lanes::store(acc + i, lanes::load(acc + i) + wv * (nodeScale * sig));
        }
    }
}

#if IRIS_LANES_HAVE_AVX2
typedef float Float8 __attribute__((vector_size(32)));
typedef int Int8 __attribute__((vector_size(32)));

/// The sigmoid shape values w · (scale · S(poly(t))) of eight lanes (grey lanes: w · greyValue).
IRIS_LANES_AVX2 [[gnu::always_inline]] inline Float8 shapeValues8(Float8 t, Float8 c0, Float8 c1, Float8 c2, Float8 scale,
                                                                  Float8 w, Float8 greyValue, Int8 grey, bool clampFree) {
    Float8 x = (c0 * t + c1) * t + c2;
    if (!clampFree) {
        const Float8 big = Float8{} + kSigmoidClamp;
        x = x < -big ? -big : (big < x ? big : x);  // std::clamp
    }
    const Float8 sig = 0.5f + x / (2.0f * __builtin_ia32_sqrtps256(1.0f + x * x));
    const Float8 shaped = w * (scale * sig);
    const Float8 flat = w * greyValue;
    return grey ? flat : shaped;
}

IRIS_LANES_AVX2 void addNodeShapesAvx2(const GridNode* nodes, const uint16_t* nodeOf, const float* weightOf, int count,
                                       const float* tl, int padded, bool clampFree, float* acc) {
    using lanes::Float4;
    if (padded == 4) {
        const Float4 t4 = lanes::load(tl);
        const Float8 t = __builtin_shufflevector(t4, t4, 0, 1, 2, 3, 0, 1, 2, 3);
        Float4 a = lanes::load(acc);
        int e = 0;
        for (; e + 1 < count; e += 2) {
            const GridNode& p = nodes[nodeOf[e]];
            const GridNode& q = nodes[nodeOf[e + 1]];
            const float wp = weightOf[e], wq = weightOf[e + 1];
            const Float8 v = shapeValues8(t, Float8{p.c0, p.c0, p.c0, p.c0, q.c0, q.c0, q.c0, q.c0},
                                          Float8{p.c1, p.c1, p.c1, p.c1, q.c1, q.c1, q.c1, q.c1},
                                          Float8{p.c2, p.c2, p.c2, p.c2, q.c2, q.c2, q.c2, q.c2},
                                          Float8{p.scale, p.scale, p.scale, p.scale, q.scale, q.scale, q.scale, q.scale},
                                          Float8{wp, wp, wp, wp, wq, wq, wq, wq},
                                          Float8{p.greyValue, p.greyValue, p.greyValue, p.greyValue, q.greyValue,
                                                 q.greyValue, q.greyValue, q.greyValue},
                                          Int8{-p.grey, -p.grey, -p.grey, -p.grey, -q.grey, -q.grey, -q.grey, -q.grey},
                                          clampFree);
            a = a + __builtin_shufflevector(v, v, 0, 1, 2, 3);  // node e, then node e + 1
            a = a + __builtin_shufflevector(v, v, 4, 5, 6, 7);
        }
        lanes::store(acc, a);
        if (e < count) addNodeShapesBaseline(nodes, nodeOf + e, weightOf + e, 1, tl, 4, clampFree, acc);
        return;
    }
    for (int e = 0; e < count; ++e) {
        const GridNode& p = nodes[nodeOf[e]];
        const Float8 c0 = Float8{} + p.c0, c1 = Float8{} + p.c1, c2 = Float8{} + p.c2, scale = Float8{} + p.scale;
        const Float8 w = Float8{} + weightOf[e], greyValue = Float8{} + p.greyValue;
        const Int8 grey = Int8{} - int(p.grey);
        int i = 0;
        for (; i + 8 <= padded; i += 8) {
            Float8 t, a;
            std::memcpy(&t, tl + i, sizeof t);
            std::memcpy(&a, acc + i, sizeof a);
            a = a + shapeValues8(t, c0, c1, c2, scale, w, greyValue, grey, clampFree);
            std::memcpy(acc + i, &a, sizeof a);
        }
        if (i < padded) addNodeShapesBaseline(nodes, nodeOf + e, weightOf + e, 1, tl + i, 4, clampFree, acc + i);
    }
}
#endif

void addNodeShapes(const GridNode* nodes, const uint16_t* nodeOf, const float* weightOf, int count, const float* tl, int padded,
                   bool clampFree, float* acc) {
#if IRIS_LANES_HAVE_AVX2
    if (lanes::useAvx2()) return addNodeShapesAvx2(nodes, nodeOf, weightOf, count, tl, padded, clampFree, acc);
#endif
    addNodeShapesBaseline(nodes, nodeOf, weightOf, count, tl, padded, clampFree, acc);
}

class EnvMapLight final : public Light {
public:
    EnvMapLight(Image img, const EnvmapLattice& lattice, const mat4& toWorld, float scale, std::string name)
        : img_(std::move(img)), lattice_(lattice), toWorld_(toWorld), toLocal_(glm::inverse(mat3(toWorld))), scale_(scale), name_(std::move(name)) {
        const int w = img_.width, h = img_.height;
        rgb_.resize(size_t(w) * h);
        std::vector<float> luminance(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                vec3 c(0.0f);
                for (int k = 0; k < std::min(3, img_.channels); ++k) c[k] = img_.at(x, y, k);
                if (img_.channels == 1) c = vec3(c.x);
                c = glm::max(c, vec3(0.0f));
                if (!isFinite(c)) c = vec3(0.0f);
                rgb_[size_t(y) * w + x] = c * scale_;
                luminance[size_t(y) * w + x] = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;  // Rec.709 Y
            }
        buildDistribution(luminance);
        img_.pixels.clear();
        img_.pixels.shrink_to_fit();
    }

    Type type() const override { return Type::Infinite; }

    std::optional<LightSample> sampleLi(const vec3& p, const vec2& u, const SampledWavelengths& wl) const override {
        std::optional<LightSample> ls = sampleLiDeferred(p, u, wl);
        if (ls) {
            ls->L = lookup(ls->uv, wl);
            ls->radianceDeferred = false;
        }
        return ls;
    }

    /// The direction and its density; the radiance (the costly part in spectral mode) is looked up
    /// at ls.uv by deferredRadiance.
    std::optional<LightSample> sampleLiDeferred(const vec3&, const vec2& u, const SampledWavelengths&) const override {
        float mapPdf;
        const vec2 uv = dist_.sampleContinuous(u, &mapPdf);
        if (mapPdf <= 0) return std::nullopt;
        const float theta = uv.y * kPi, phi = uv.x * 2.0f * kPi;
        const float sinTheta = std::sin(theta);
        if (sinTheta <= 0) return std::nullopt;
        const vec3 local(sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi));
        LightSample ls;
        ls.wi = glm::normalize(mat3(toWorld_) * local);
        ls.pdf = mapPdf / (2.0f * kPi * kPi * sinTheta);
        ls.infinite = true;
        ls.uv = uv;
        ls.radianceDeferred = true;
        return ls;
    }

    SampledSpectrum deferredRadiance(const LightSample& ls, const SampledWavelengths& wl) const override {
        return ls.radianceDeferred ? lookup(ls.uv, wl) : ls.L;
    }

    float pdfLi(const vec3&, const vec3& wi, const SurfaceInteraction*) const override {
        const vec3 v = glm::normalize(toLocal_ * wi);
        const float sinTheta = safeSqrt(1.0f - v.y * v.y);
        if (sinTheta <= 0) return 0.0f;
        return dist_.pdf(dirToUV(v)) / (2.0f * kPi * kPi * sinTheta);
    }

    SampledSpectrum Le(const TextureQuery&, const vec3&, const vec3& w, const SampledWavelengths& wl) const override {
        return lookup(dirToUV(glm::normalize(toLocal_ * w)), wl);
    }

private:
    static vec2 dirToUV(const vec3& v) {
        float u = std::atan2(v.x, -v.z) * kInv2Pi;
        if (u < 0) u += 1.0f;
        return vec2(u, safeAcos(v.y) * kInvPi);
    }

    /// The four texels around uv and their bilinear weights (envmap_lattice.h).
    struct Taps {
        int index[4];
        float weight[4];
    };
    Taps taps(const vec2& uv) const {
        int x0, x1, y0, y1;
        float fx, fy;
        lattice_.u.taps(uv.x, x0, x1, fx);
        lattice_.v.taps(uv.y, y0, y1, fy);
        const int w = img_.width;
        return {{y0 * w + x0, y0 * w + x1, y1 * w + x0, y1 * w + x1},
                {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy}};
    }

    /// Sampling weights: per cell of the (u.texels × cellsV) grid, the exact average of the
    /// bilinear luminance over the cell × sinθ at its centre, plus a floor.
    void buildDistribution(const std::vector<float>& luminance) {
        const int nu = lattice_.u.texels, nv = lattice_.cellsV, w = img_.width;
        std::vector<float> weight(size_t(nu) * nv);
        for (int j = 0; j < nv; ++j) {
            const float sinTheta = std::sin(kPi * (j + 0.5f) / nv);
            for (int i = 0; i < nu; ++i) {
                double avg = 0;
                forEachAverageWeight(lattice_.v, double(j) / nv, double(j + 1) / nv, [&](int ty, double wy) {
                    forEachAverageWeight(lattice_.u, double(i) / nu, double(i + 1) / nu,
                                         [&](int tx, double wx) { avg += wy * wx * luminance[size_t(ty) * w + tx]; });
                });
                weight[size_t(j) * nu + i] = (float(avg) + 1e-6f) * sinTheta;
            }
        }
        dist_ = Distribution2D(weight, nu, nv);
    }

    SampledSpectrum lookup(const vec2& uv, const SampledWavelengths& wl) const {
        const Taps t = taps(uv);
        SampledSpectrum s(wl.size());
        if (wl.isRGB()) {
            vec3 c(0.0f);
            for (int k = 0; k < 4; ++k) c += t.weight[k] * rgb_[t.index[k]];
            for (int i = 0; i < 3; ++i) s[i] = c[i];
            return s;
        }
        // Texel k has spectrum m_k · S(c_k) (scale m_k = max component, chromaticity c_k).
        // Mitsuba 0.6 interpolates the texels' spectra: Σ w_k m_k S(c_k). Mitsuba 3 interpolates
        // the normalised spectra and the scales separately and multiplies them (eval_spectrum:
        // s = Σ w_k S_k, f = Σ w_k f_k, result s · f), which differs at edges between bright and
        // dark texels (its spectral references differ there from its RGB ones).
        if (!gridBuilt_.load(std::memory_order_acquire)) std::call_once(gridOnce_, [this] { buildGrid(); });
        const int n = wl.size();
        const int padded = SampledSpectrum::paddedSize(n);
        // The wavelengths' normalised coordinate t of the sigmoid polynomials, once per lookup.
        alignas(16) float tl[kMaxWavelengths];
        alignas(16) float acc[kMaxWavelengths];
        for (int i = 0; i < padded; i += 4) {
            lanes::store(tl + i, (lanes::load(wl.lambdas() + i) - 360.0f) * (1.0f / 470.0f));
            lanes::store(acc + i, lanes::broadcast(0.0f));
        }
        uint16_t nodeBuf[16];
        alignas(16) float weightOf[16];
        const uint16_t* nodeOf = nodeBuf;
        float scale = 0.0f;
        int count = blockMerge(t, weightOf, nodeOf, scale);
        if (count < 0) count = mergeNodes(t, nodeBuf, weightOf, scale);
        addNodeShapes(nodes_.data(), nodeOf, weightOf, count, tl, padded, clampFree_, acc);
        if (scale <= 0) return s;
        const float common = d65Factor_ * (lattice_.separateScale ? scale : 1.0f);
        const float* d65 = wl.d65Lanes();  // cie::d65 at the path's wavelengths, computed at sampling
        for (int i = 0; i < n; ++i) s[i] = acc[i] * (common * d65[i]);
        return s;
    }

    /// The four texels' corner nodes and weights, node by node (the general merge): returns the node
    /// count, fills nodeOf and weightOf, adds the interpolated scale to `scale`.
    int mergeNodes(const Taps& t, uint16_t* nodeOf, float* weightOf, float& scale) const {
        // The four texels' corner nodes and weights, a node that several texels share taken once
        // with the sum of its weights (neighbouring texels mostly lie in the same grid cell: about
        // 6 distinct nodes of 16 on the museum map). The sum is the same as texel by texel up to
        // float rounding.
        int count = 0;
        const EnvmapTexelShape* first = nullptr;  // the first texel with weight
        bool sameCell = true;               // every texel with weight uses first's nodes
        for (int k = 0; k < 4; ++k) {
            if (t.weight[k] <= 0) continue;
            const EnvmapTexelShape& texel = texelShapes_[t.index[k]];
            const float m = texel.m;
            if (m <= 0) continue;
            const float weight = t.weight[k] * (lattice_.separateScale ? 1.0f : m);
            scale += t.weight[k] * m;
            if (!first) {
                first = &texel;
                for (int j = 0; j < 4; ++j) weightOf[j] = texel.p[j] * weight;
                continue;
            }
            if (sameCell && texel.cell() == first->cell()) {
                for (int j = 0; j < 4; ++j) weightOf[j] += texel.p[j] * weight;
                continue;
            }
            if (sameCell) {  // from here on, node by node
                sameCell = false;
                for (int j = 0; j < 4; ++j)
                    if (weightOf[j] > 0) {
                        nodeOf[count] = first->node[j];
                        weightOf[count++] = weightOf[j];
                    }
            }
            for (int j = 0; j < 4; ++j) {
                const float w = texel.p[j] * weight;
                if (w <= 0) continue;
                int e = 0;
                while (e < count && nodeOf[e] != texel.node[j]) ++e;
                if (e == count) {
                    nodeOf[count] = texel.node[j];
                    weightOf[count++] = w;
                } else {
                    weightOf[e] += w;
                }
            }
        }
        if (first && sameCell)
            for (int j = 0; j < 4; ++j)
                if (weightOf[j] > 0) {
                    nodeOf[count] = first->node[j];
                    weightOf[count++] = weightOf[j];
                }
        return count;
    }

    /// mergeNodes from the block's precomputed node list (EnvmapNodeBlocks), the same nodes, order
    /// and weights bit for bit, where it applies: the texels form block index[0] (u wraps to the
    /// next column, and the rows differ: not clamped at a pole), the block is stored, and every
    /// texel's least contribution pMin · W_k is positive (then all are, rounding being monotonic).
    /// Returns −1 where it does not apply.
    int blockMerge(const Taps& t, float* weightOf, const uint16_t*& nodeOf, float& scale) const {
        if (t.index[2] == t.index[0] || !lattice_.u.periodic) return -1;
        const int block = t.index[0];
        const int count = blocks_.count(block);
        if (count == 0) return -1;
        lanes::Float4 w;
        float s = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const EnvmapTexelShape& texel = texelShapes_[t.index[k]];
            w[k] = t.weight[k] * (lattice_.separateScale ? 1.0f : texel.m);
            if (!(texel.pMin * w[k] > 0)) return -1;
            s += t.weight[k] * texel.m;
        }
        blocks_.weights(block, w, weightOf);
        nodeOf = blocks_.nodes(block);
        scale = s;
        return count;
    }

    static int gridIndex(int x, int y, int z) { return (z * kGrid + y) * kGrid + x; }

    /// The grid nodes some texel uses (fitted once, on the first spectral lookup) and every
    /// texel's TexelShape.
    void buildGrid() const {
        std::vector<int> compact(kGrid * kGrid * kGrid, -1);  // grid index → index into nodes_
        texelShapes_.resize(rgb_.size());
        for (size_t i = 0; i < rgb_.size(); ++i) {
            const vec3& c = rgb_[i];
            const float m = std::max({c.x, c.y, c.z});
            if (m <= 0) continue;
            EnvmapTexelShape& texel = texelShapes_[i];
            texel.m = m;
            const vec3 g = c / m * float(kGrid - 1);
            const int x0 = std::min(int(g.x), kGrid - 2), y0 = std::min(int(g.y), kGrid - 2), z0 = std::min(int(g.z), kGrid - 2);
            const vec3 f = g - vec3(x0, y0, z0);
            int used = 0;
            for (int corner = 0; corner < 8; ++corner) {
                const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
                const float p = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
                if (p <= 0) continue;
                if (used == 4) fail("envmap: a chromaticity with more than four grid corners");  // c/m has a component 1
                int& slot = compact[gridIndex(x0 + dx, y0 + dy, z0 + dz)];
                if (slot < 0) {
                    slot = int(nodes_.size());
                    nodes_.push_back(fitNode(x0 + dx, y0 + dy, z0 + dz));
                }
                texel.p[used] = p;
                texel.node[used] = uint16_t(slot);
                texel.pMin = std::min(texel.pMin, p);
                ++used;
            }
        }
        blocks_ = EnvmapNodeBlocks(texelShapes_, img_.width, img_.height, kMaxBlockBytes);
        // For t = (λ − 360)/470 ∈ [0, 1] (every lane's λ is in [kLambdaMin, kLambdaMax]) the
        // polynomial stays within |c0| + |c1| + |c2| (times 1 + 3 float roundings): below 2^62 the
        // clamp at 2^63 cannot act.
        clampFree_ = true;
        for (const GridNode& node : nodes_)
            if (!node.grey && !(std::abs(node.c0) + std::abs(node.c1) + std::abs(node.c2) < 4.611686e18f)) clampFree_ = false;
        gridBuilt_.store(true, std::memory_order_release);
    }

    /// The shape of the grid node (x, y, z): the spectrum makeRGBSpectrum(rgb, Illuminant) returns.
    GridNode fitNode(int x, int y, int z) const {
        const RGBSpectrum sp(vec3(x, y, z) / float(kGrid - 1), SpectrumKind::Illuminant);
        d65Factor_ = sp.d65Factor();
        GridNode node;
        node.c0 = sp.sigmoid().c0;
        node.c1 = sp.sigmoid().c1;
        node.c2 = sp.sigmoid().c2;
        node.scale = sp.shapeScale();
        node.grey = sp.isGrey();
        node.greyValue = sp.isGrey() ? sp.shapeValue(kLambdaMin) : 0.0f;
        return node;
    }

    Image img_;  // size only (pixels released after construction)
    EnvmapLattice lattice_;
    std::vector<vec3> rgb_;
    mat4 toWorld_;
    mat3 toLocal_;
    float scale_;
    std::string name_;
    Distribution2D dist_;
    mutable std::once_flag gridOnce_;
    mutable std::vector<GridNode> nodes_;  // the nodes some texel uses
    mutable std::vector<EnvmapTexelShape> texelShapes_;  // per texel, as rgb_
    mutable EnvmapNodeBlocks blocks_;  // per 2×2 texel block, its merged node list (buildGrid)
    mutable std::atomic<bool> gridBuilt_{false};
    mutable bool clampFree_ = false;  // no node's polynomial reaches the sigmoid's clamp (buildGrid)
    mutable float d65Factor_ = 0;  // the corners' common D65 normalisation (RGBSpectrum::d65Factor)
};

std::shared_ptr<Light> createEnvMap(const Properties& p) {
    const std::string file = p.getString("filename");
    Image img = withLocation(p.locationOf("filename"), [&] { return readImage(file); });
    // Texel placement by convention (docs/scene_format.md): Mitsuba 3 puts the first and last
    // rows on the poles and, like Mitsuba 3, needs at least 2×3 texels; Mitsuba 0.6 any size.
    const bool mitsuba3 = getConvention(p) == MitsubaConvention::Mitsuba3;
    if (img.width < 1 || img.height < 1) failAt(p.locationOf("filename"), file, ": empty environment map");
    if (mitsuba3 && (img.width < 2 || img.height < 3))
        failAt(p.locationOf("filename"), file, ": an environment map needs at least 2x3 pixels (Mitsuba 3's rule; convention \"mitsuba0.6\" ",
               "takes any size), this one is ", img.width, "x", img.height);
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0) || !std::isfinite(scale)) failAt(p.locationOf("scale"), "envmap scale must be a finite value >= 0");
    const EnvmapLattice lattice = mitsuba3 ? EnvmapLattice::mitsuba3(img.width, img.height) : EnvmapLattice::mitsuba06(img.width, img.height);
    return std::make_shared<EnvMapLight>(std::move(img), lattice, p.getTransform("to_world"), scale, file);
}

}  // namespace

IRIS_REGISTER(LightRegistry, "envmap", createEnvMap);

}  // namespace iris
