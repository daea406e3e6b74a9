#include "render/film.h"

#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace iris {

PixelFilter::PixelFilter(const CameraDescription& d) : type_(d.filter), radius_(d.filterRadius), stddev_(d.gaussianStddev) {
    if (!(radius_ > 0)) fail("pixel filter radius must be positive, got ", radius_);
    if (!(stddev_ > 0)) fail("gaussian filter stddev must be positive, got ", stddev_);
    if (type_ != CameraDescription::Filter::Gaussian) return;
    // Truncated Gaussian on [−3σ, 3σ]: CDF(x) = (erf(x/(σ√2)) + erf(a/(σ√2))) / (2 erf(a/(σ√2))).
    // Invert at 1025 evenly spaced probabilities by Newton's method on erf (in double).
    const int n = 1025;
    const double a = 3.0 * stddev_, s = stddev_ * std::sqrt(2.0), ea = std::erf(a / s);
    inverseCdf_.resize(n);
    for (int i = 0; i < n; ++i) {
        const double target = (2.0 * i / (n - 1) - 1.0) * ea;  // erf(x/s) = target
        double x = 0.0;
        for (int it = 0; it < 50; ++it) {
            const double f = std::erf(x / s) - target;
            const double df = 2.0 / std::sqrt(M_PI) * std::exp(-(x / s) * (x / s)) / s;
            const double next = std::clamp(x - f / df, -a, a);
            if (std::abs(next - x) < 1e-12) break;
            x = next;
        }
        inverseCdf_[i] = float(x);
    }
    inverseCdf_.front() = float(-a);
    inverseCdf_.back() = float(a);
}

float PixelFilter::sample1D(float u) const {
    const float t = u * float(inverseCdf_.size() - 1);
    const int i = std::min(int(t), int(inverseCdf_.size()) - 2);
    const float f = t - float(i);
    return (1.0f - f) * inverseCdf_[i] + f * inverseCdf_[i + 1];
}

vec2 PixelFilter::sample(const vec2& u) const {
    if (type_ == CameraDescription::Filter::Box) return (2.0f * u - vec2(1.0f)) * radius_;
    return vec2(sample1D(u.x), sample1D(u.y));
}

Film::Film(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) fail("film size must be positive, got ", width, "x", height);
    const uint64_t n = uint64_t(width) * uint64_t(height);
    if (n > (uint64_t(1) << 28)) fail("film of ", width, "x", height, " pixels is too large (limit 2^28 pixels)");
    sum_.assign(3 * n, 0.0);
    sumSq_.assign(3 * n, 0.0);
    count_.assign(n, 0);
}

vec3 Film::pixel(int x, int y) const {
    const size_t i = size_t(y) * width_ + x;
    if (count_[i] == 0) return vec3(0.0f);
    const double inv = 1.0 / count_[i];
    return vec3(float(sum_[3 * i] * inv), float(sum_[3 * i + 1] * inv), float(sum_[3 * i + 2] * inv));
}

uint64_t Film::totalSamples() const {
    uint64_t s = 0;
    for (uint32_t c : count_) s += c;
    return s;
}

uint32_t Film::minSampleCount() const {
    uint32_t m = UINT32_MAX;
    for (uint32_t c : count_) m = std::min(m, c);
    return count_.empty() ? 0 : m;
}

std::vector<float> Film::meanImage() const {
    std::vector<float> img(3 * size_t(width_) * height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const vec3 p = pixel(x, y);
            const size_t i = 3 * (size_t(y) * width_ + x);
            img[i] = p.x;
            img[i + 1] = p.y;
            img[i + 2] = p.z;
        }
    return img;
}

std::vector<float> Film::varianceOfMeanImage() const {
    std::vector<float> img(3 * size_t(width_) * height_, 0.0f);
    for (size_t i = 0; i < count_.size(); ++i) {
        const double n = count_[i];
        if (n < 2) continue;
        for (int c = 0; c < 3; ++c) {
            double mean = sum_[3 * i + c] / n;
            if (hasMomentSpace_) {  // E[(M v)_c] = Σ_k M_ck E[v_k] (glm is column-major: M[k][c])
                mean = 0.0;
                for (int k = 0; k < 3; ++k) mean += double(momentSpace_[k][c]) * sum_[3 * i + k] / n;
            }
            const double var = std::max(0.0, (sumSq_[3 * i + c] - n * mean * mean) / (n - 1));
            img[3 * i + c] = float(var / n);
        }
    }
    return img;
}

namespace {
constexpr char kMagic[8] = {'I', 'R', 'I', 'S', 'C', 'K', 'P', '2'};
}

void Film::save(const std::string& path, const std::string& header) const {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) fail(path, ": cannot write checkpoint");
        const uint64_t hlen = header.size();
        f.write(kMagic, 8);
        f.write(reinterpret_cast<const char*>(&hlen), sizeof hlen);
        f.write(header.data(), std::streamsize(hlen));
        f.write(reinterpret_cast<const char*>(&width_), sizeof width_);
        f.write(reinterpret_cast<const char*>(&height_), sizeof height_);
        f.write(reinterpret_cast<const char*>(sum_.data()), std::streamsize(sum_.size() * sizeof(double)));
        f.write(reinterpret_cast<const char*>(sumSq_.data()), std::streamsize(sumSq_.size() * sizeof(double)));
        f.write(reinterpret_cast<const char*>(count_.data()), std::streamsize(count_.size() * sizeof(uint32_t)));
        if (!f) fail(path, ": error while writing checkpoint");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) fail(path, ": cannot move checkpoint into place");
}

void Film::load(const std::string& path, const std::string& header) {
    std::ifstream f(path, std::ios::binary);
    if (!f) fail(path, ": cannot open checkpoint");
    char magic[8];
    uint64_t hlen = 0;
    f.read(magic, 8);
    f.read(reinterpret_cast<char*>(&hlen), sizeof hlen);
    if (!f || std::string(magic, 8) != std::string(kMagic, 8) || hlen > (1u << 20)) fail(path, ": not an iris checkpoint");
    std::string h(hlen, '\0');
    f.read(h.data(), std::streamsize(hlen));
    if (h != header) fail(path, ": checkpoint was made with a different scene or settings");
    int w = 0, hgt = 0;
    f.read(reinterpret_cast<char*>(&w), sizeof w);
    f.read(reinterpret_cast<char*>(&hgt), sizeof hgt);
    if (!f || w != width_ || hgt != height_) fail(path, ": checkpoint film size differs");
    f.read(reinterpret_cast<char*>(sum_.data()), std::streamsize(sum_.size() * sizeof(double)));
    f.read(reinterpret_cast<char*>(sumSq_.data()), std::streamsize(sumSq_.size() * sizeof(double)));
    f.read(reinterpret_cast<char*>(count_.data()), std::streamsize(count_.size() * sizeof(uint32_t)));
    if (!f) fail(path, ": checkpoint is truncated");
}

}  // namespace iris
