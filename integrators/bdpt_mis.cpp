#include "integrators/bdpt_mis.h"

#include <vector>

namespace iris {

namespace {

/// A vertex's densities as one strategy sees them (pbrt-v4 changes them in place and restores them).
struct Densities {
    float fwd = 0, rev = 0;
    bool delta = false;
};

float remap0(float f) { return f != 0.0f ? f : 1.0f; }
float heuristic(float ratio, MISHeuristic h) { return h == MISHeuristic::Power ? ratio * ratio : ratio; }

}  // namespace

float misWeight(const Scene& scene, const BDPTVertex* light, const BDPTVertex* camera, const BDPTVertex& sampled, int s, int t,
                MISHeuristic h, const StrategySet& strategies) {
    if (s + t == 2) return 1.0f;
    const BDPTVertex* qs = s > 0 ? (s == 1 ? &sampled : &light[s - 1]) : nullptr;
    const BDPTVertex* pt = t == 1 ? &sampled : &camera[t - 1];
    const BDPTVertex* qsMinus = s > 1 ? &light[s - 2] : nullptr;
    const BDPTVertex* ptMinus = t > 1 ? &camera[t - 2] : nullptr;
    thread_local std::vector<Densities> lightD, cameraD;
    lightD.resize(size_t(s));
    cameraD.resize(size_t(t));
    for (int i = 0; i < s; ++i) lightD[size_t(i)] = {light[i].pdfFwd, light[i].pdfRev, light[i].delta};
    for (int i = 0; i < t; ++i) cameraD[size_t(i)] = {camera[i].pdfFwd, camera[i].pdfRev, camera[i].delta};
    if (s == 1) lightD[0] = {sampled.pdfFwd, sampled.pdfRev, sampled.delta};
    if (t == 1) cameraD[0] = {sampled.pdfFwd, sampled.pdfRev, sampled.delta};
    // The connection's two ends are not delta; their reverse densities are the other side's
    // (pbrt-v4 MISWeight, the scoped assignments a2 … a7).
    cameraD[size_t(t - 1)].delta = false;
    if (qs) lightD[size_t(s - 1)].delta = false;
    cameraD[size_t(t - 1)].rev = s > 0 ? vertexPdf(scene, *qs, qsMinus, *pt) : lightOriginPdf(scene, *pt, *ptMinus);
    if (ptMinus) cameraD[size_t(t - 2)].rev = s > 0 ? vertexPdf(scene, *pt, qs, *ptMinus) : lightPdf(scene, *pt, *ptMinus);
    if (qs) lightD[size_t(s - 1)].rev = vertexPdf(scene, *pt, ptMinus, *qs);
    if (qsMinus) lightD[size_t(s - 2)].rev = vertexPdf(scene, *qs, pt, *qsMinus);

    // Splits with fewer camera vertices: (s + t − i, i) for i = t − 1 … 1.
    const auto used = [&](int sSplit, int tSplit) {
        return (tSplit != 1 || strategies.lightImage) && (sSplit != 1 || strategies.sampleDirect);
    };
    float sum = 0.0f, ratio = 1.0f;
    for (int i = t - 1; i > 0; --i) {
        ratio *= remap0(cameraD[size_t(i)].rev) / remap0(cameraD[size_t(i)].fwd);
        if (used(s + t - i, i) && !cameraD[size_t(i)].delta && !cameraD[size_t(i - 1)].delta) sum += heuristic(ratio, h);
    }
    // Splits with fewer light vertices: (i, s + t − i) for i = s − 1 … 0.
    ratio = 1.0f;
    for (int i = s - 1; i >= 0; --i) {
        ratio *= remap0(lightD[size_t(i)].rev) / remap0(lightD[size_t(i)].fwd);
        const bool deltaBefore = i > 0 ? lightD[size_t(i - 1)].delta : (s == 1 ? sampled.isDeltaLight() : light[0].isDeltaLight());
        if (used(i, s + t - i) && !lightD[size_t(i)].delta && !deltaBefore) sum += heuristic(ratio, h);
    }
    return 1.0f / (1.0f + sum);
}

}  // namespace iris
