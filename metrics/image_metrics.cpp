// Image error metrics. Definitions (with their sources) are in docs/metrics.md:
//  MSE, relMSE = (x − r)² / (r² + ε) with ε = 1e-2 (Rousselle, Knaus, Zwicker 2011, "Adaptive sampling
//  and reconstruction using greedy error minimization", SIGGRAPH Asia), PSNR on values clamped to
//  [0,1] with peak 1, SMAPE = |x − r| / (|x| + |r| + ε) with ε = 1e-2 (symmetric mean absolute
//  percentage error as used by Vogels et al. 2018, "Denoising with kernel prediction and asymmetric
//  loss functions", SIGGRAPH), and CIEDE2000 (Sharma, Wu, Dalal 2005) in CIELAB from linear Rec.709 (D65).
#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "metrics/color_difference.h"

namespace iris {

namespace {

void checkSameSize(const Image& test, const Image& ref) {
    if (test.width != ref.width || test.height != ref.height)
        fail("image size mismatch: test is ", test.width, "x", test.height, ", reference is ", ref.width, "x",
             ref.height);
    if (test.pixels.size() != test.pixelCount() * size_t(test.channels) ||
        ref.pixels.size() != ref.pixelCount() * size_t(ref.channels))
        fail("image buffer does not match its declared size");
}

Lab labOf(const Image& img, size_t p, const std::vector<int>& ch) {
    const float* px = img.pixels.data() + p * size_t(img.channels);
    if (ch.size() == 1) return linearRec709ToLab(px[ch[0]], px[ch[0]], px[ch[0]]);
    return linearRec709ToLab(px[ch[0]], px[ch[1]], px[ch[2]]);
}

bool finitePixel(const Image& img, size_t p, const std::vector<int>& ch) {
    for (int c : ch)
        if (!std::isfinite(img.pixels[p * size_t(img.channels) + size_t(c)])) return false;
    return true;
}

}  // namespace

void matchedChannels(const Image& test, const Image& ref, std::vector<int>& ct, std::vector<int>& cr) {
    checkSameSize(test, ref);
    ct = colourChannels(test);
    cr = colourChannels(ref);
    if (ct.size() != cr.size())
        fail("channel mismatch: test has ", ct.size(), " colour channel(s), reference has ", cr.size());
}

std::vector<int> colourChannels(const Image& img) {
    const int r = img.channelIndex("R"), g = img.channelIndex("G"), b = img.channelIndex("B");
    if (r >= 0 && g >= 0 && b >= 0) return {r, g, b};
    if (img.channels >= 3) return {0, 1, 2};
    if (img.channels >= 1) return {0};
    fail("image has no channels");
}

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    // Nearest rank: the smallest value with at least q% of the values at or below it.
    const size_t n = values.size();
    size_t rank = size_t(std::ceil(std::clamp(q, 0.0, 100.0) / 100.0 * double(n)));
    rank = std::clamp<size_t>(rank, 1, n);
    std::nth_element(values.begin(), values.begin() + long(rank - 1), values.end());
    return values[rank - 1];
}

ImageErrors compareImages(const Image& test, const Image& ref) {
    std::vector<int> ct, cr;
    matchedChannels(test, ref, ct, cr);
    ImageErrors e;
    e.width = test.width;
    e.height = test.height;
    e.channels = int(ct.size());
    double sumSq = 0, sumRel = 0, sumSmape = 0, sumClamped = 0, sumDE = 0;
    size_t nValues = 0;
    std::vector<double> deltaE;
    deltaE.reserve(test.pixelCount());
    for (size_t p = 0; p < test.pixelCount(); ++p) {
        if (!finitePixel(test, p, ct) || !finitePixel(ref, p, cr)) {
            e.nonFinite += 1;
            continue;
        }
        for (size_t k = 0; k < ct.size(); ++k) {
            const double x = test.pixels[p * size_t(test.channels) + size_t(ct[k])];
            const double r = ref.pixels[p * size_t(ref.channels) + size_t(cr[k])];
            const double d = x - r;
            sumSq += d * d;
            sumRel += d * d / (r * r + kRelMSEEpsilon);
            sumSmape += std::abs(d) / (std::abs(x) + std::abs(r) + kSmapeEpsilon);
            const double dc = std::clamp(x, 0.0, 1.0) - std::clamp(r, 0.0, 1.0);
            sumClamped += dc * dc;
            ++nValues;
        }
        const double de = ciede2000(labOf(test, p, ct), labOf(ref, p, cr));
        deltaE.push_back(de);
        sumDE += de;
        e.maxDeltaE00 = std::max(e.maxDeltaE00, de);
    }
    if (nValues == 0) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        e.mse = e.relMse = e.smape = e.psnr = e.meanDeltaE00 = e.p99DeltaE00 = e.maxDeltaE00 = nan;
        return e;
    }
    e.mse = sumSq / double(nValues);
    e.relMse = sumRel / double(nValues);
    e.smape = sumSmape / double(nValues);
    const double mseClamped = sumClamped / double(nValues);
    e.psnr = mseClamped > 0 ? 10.0 * std::log10(1.0 / mseClamped) : std::numeric_limits<double>::infinity();
    e.meanDeltaE00 = sumDE / double(deltaE.size());
    e.p99DeltaE00 = percentile(std::move(deltaE), 99.0);
    return e;
}

std::vector<ChannelErrors> channelErrors(const Image& test, const Image& ref, std::vector<std::string> names) {
    checkSameSize(test, ref);
    if (names.empty())
        for (const std::string& n : test.channelNames)
            if (ref.channelIndex(n) >= 0) names.push_back(n);
    std::vector<ChannelErrors> out;
    for (const std::string& name : names) {
        const int ct = test.channelIndex(name), cr = ref.channelIndex(name);
        if (ct < 0 || cr < 0) fail("channel '", name, "' is missing in the ", ct < 0 ? "test" : "reference", " image");
        ChannelErrors e{name};
        for (size_t p = 0; p < test.pixelCount(); ++p) {
            const double x = test.pixels[p * size_t(test.channels) + size_t(ct)];
            const double r = ref.pixels[p * size_t(ref.channels) + size_t(cr)];
            if (!std::isfinite(x) || !std::isfinite(r)) continue;
            const double d = x - r;
            e.mse += d * d;
            e.relMse += d * d / (r * r + kRelMSEEpsilon);
            e.smape += std::abs(d) / (std::abs(x) + std::abs(r) + kSmapeEpsilon);
            ++e.count;
        }
        const double n = e.count ? double(e.count) : std::numeric_limits<double>::quiet_NaN();
        e.mse /= n;
        e.relMse /= n;
        e.smape /= n;
        out.push_back(e);
    }
    return out;
}

Image deltaE00Map(const Image& test, const Image& ref) {
    std::vector<int> ct, cr;
    matchedChannels(test, ref, ct, cr);
    Image out(test.width, test.height, 1);
    out.channelNames = {"Y"};
    for (size_t p = 0; p < test.pixelCount(); ++p)
        out.pixels[p] = finitePixel(test, p, ct) && finitePixel(ref, p, cr)
                            ? float(ciede2000(labOf(test, p, ct), labOf(ref, p, cr)))
                            : std::numeric_limits<float>::quiet_NaN();
    return out;
}

Image differenceImage(const Image& test, const Image& ref) {
    std::vector<int> ct, cr;
    matchedChannels(test, ref, ct, cr);
    Image out(test.width, test.height, int(ct.size()));
    for (size_t p = 0; p < test.pixelCount(); ++p)
        for (size_t k = 0; k < ct.size(); ++k)
            out.pixels[p * ct.size() + k] = test.pixels[p * size_t(test.channels) + size_t(ct[k])] -
                                            ref.pixels[p * size_t(ref.channels) + size_t(cr[k])];
    return out;
}

PixelStatistics pixelStatistics(const std::vector<Image>& renders) {
    if (renders.size() < 2) fail("pixel statistics need at least 2 renders, got ", renders.size());
    const Image& first = renders.front();
    for (const Image& img : renders)
        if (img.width != first.width || img.height != first.height || img.channels != first.channels)
            fail("pixel statistics: renders differ in size or channel count (", img.width, "x", img.height, "x",
                 img.channels, " vs ", first.width, "x", first.height, "x", first.channels, ")");
    PixelStatistics s;
    s.count = int(renders.size());
    s.mean = s.variance = s.varianceOfMean = Image(first.width, first.height, first.channels);
    s.mean.channelNames = s.variance.channelNames = s.varianceOfMean.channelNames = first.channelNames;
    const double k = double(renders.size());
    for (size_t i = 0; i < first.pixels.size(); ++i) {
        // Two-pass mean and unbiased sample variance.
        double mean = 0;
        for (const Image& img : renders) mean += img.pixels[i];
        mean /= k;
        double ss = 0;
        for (const Image& img : renders) ss += (img.pixels[i] - mean) * (img.pixels[i] - mean);
        const double var = ss / (k - 1.0);
        s.mean.pixels[i] = float(mean);
        s.variance.pixels[i] = float(var);
        s.varianceOfMean.pixels[i] = float(var / k);
    }
    return s;
}

NoiseComparison compareWithinNoise(const Image& test, const Image& testVariance, const Image& ref,
                                   const Image& refVariance) {
    checkSameSize(test, ref);
    checkSameSize(test, testVariance);
    checkSameSize(test, refVariance);
    if (test.channels != ref.channels || test.channels != testVariance.channels ||
        test.channels != refVariance.channels)
        fail("noise comparison: images and variances must have the same channel count");
    NoiseComparison out;
    double sumZ2 = 0;
    size_t above = 0;
    for (size_t i = 0; i < test.pixels.size(); ++i) {
        const double var = double(testVariance.pixels[i]) + double(refVariance.pixels[i]);
        const double d = double(test.pixels[i]) - double(ref.pixels[i]);
        if (!(var > 0) || !std::isfinite(var) || !std::isfinite(d)) continue;
        const double z2 = d * d / var;
        sumZ2 += z2;
        if (z2 > 9.0) ++above;
        ++out.count;
    }
    if (out.count > 0) {
        out.meanSquaredZ = sumZ2 / double(out.count);
        out.fractionAbove3 = double(above) / double(out.count);
    }
    return out;
}

}  // namespace iris
