#include "render/spectral_film.h"

#include <algorithm>

#include "core/error.h"

namespace iris {

SpectralFilm::SpectralFilm(int width, int height, int bins)
    : width_(width), height_(height), bins_(bins), binWidth_((kLambdaMax - kLambdaMin) / float(bins)) {
    if (bins < 1 || bins > int(kLambdaMax - kLambdaMin)) fail("spectral bins must be in [1, ", int(kLambdaMax - kLambdaMin), "], got ", bins);
    sum_.assign(size_t(width) * height * bins, 0.0);
    count_.assign(size_t(width) * height, 0);
}

void SpectralFilm::addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& wl) {
    const size_t pixel = size_t(y) * width_ + x;
    double* sums = &sum_[pixel * bins_];
    const double n = wl.size();
    for (int i = 0; i < wl.size(); ++i) {
        if (!(wl.pdf(i) > 0)) continue;
        const int b = std::clamp(int((wl.lambda(i) - kLambdaMin) / binWidth_), 0, bins_ - 1);
        sums[b] += double(L[i]) / (n * double(wl.pdf(i)) * double(binWidth_));  // (1/N) L / (p Δ)
    }
    count_[pixel] += 1;
}

std::vector<float> SpectralFilm::meanImage() const {
    std::vector<float> img(sum_.size(), 0.0f);
    for (size_t p = 0; p < count_.size(); ++p)
        if (count_[p] > 0)
            for (int b = 0; b < bins_; ++b) img[p * bins_ + b] = float(sum_[p * bins_ + b] / count_[p]);
    return img;
}

}  // namespace iris
