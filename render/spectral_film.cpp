#include "render/spectral_film.h"

#include "core/error.h"
#include "core/io/spectral_layout.h"

namespace iris {

SpectralFilm::SpectralFilm(int width, int height, const SpectralBins& bins) : width_(width), height_(height), bins_(bins) {
    if (width <= 0 || height <= 0) fail("spectral film size must be positive, got ", width, "x", height);
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    const uint64_t values = pixels * uint64_t(bins.count());
    if (values > (uint64_t(1) << 28))
        fail("spectral film of ", width, "x", height, " pixels x ", bins.count(), " bins is too large (limit 2^28 values; use wider bins)");
    sum_.assign(values, 0.0);
    count_.assign(pixels, 0);
}

void SpectralFilm::addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& wl) {
    const size_t pixel = size_t(y) * size_t(width_) + size_t(x);
    double* sums = &sum_[pixel * size_t(bins_.count())];
    const int n = wl.size();
    for (int i = 0; i < n; ++i) {
        if (wl.pdf(i) == 0.0f) continue;  // a terminated secondary wavelength contributes nothing
        const int b = bins_.find(wl.lambda(i));
        if (b < 0) continue;
        sums[b] += double(L[i]) / (double(n) * double(wl.pdf(i)) * bins_.width(b));
    }
    ++count_[pixel];
}

Image SpectralFilm::image() const {
    const int nb = bins_.count();
    Image img(width_, height_, nb);
    img.channelNames.clear();
    for (int b = 0; b < nb; ++b) img.channelNames.push_back(spectralChannelName(bins_.centre(b)));
    for (size_t p = 0; p < img.pixelCount(); ++p) {
        const double inv = count_[p] > 0 ? 1.0 / count_[p] : 0.0;
        for (int b = 0; b < nb; ++b) img.pixels[p * size_t(nb) + size_t(b)] = float(sum_[p * size_t(nb) + size_t(b)] * inv);
    }
    return img;
}

}  // namespace iris
