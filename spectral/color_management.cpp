#include "spectral/color_management.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/source_tree.h"

namespace OCIO = OCIO_NAMESPACE;

namespace iris {

struct ColorManager::Impl {
    std::string path;
    OCIO::ConstConfigRcPtr config;
};

namespace {

// Apply a processor to interleaved RGB floats in place, in chunks (PackedImageDesc takes long
// dimensions; chunking also keeps huge images safe).
void applyProcessor(const OCIO::ConstProcessorRcPtr& proc, float* rgb, size_t pixelCount) {
    if (pixelCount == 0) return;
    const OCIO::ConstCPUProcessorRcPtr cpu = proc->getDefaultCPUProcessor();
    constexpr size_t kChunk = size_t(1) << 24;
    for (size_t start = 0; start < pixelCount; start += kChunk) {
        const size_t n = std::min(kChunk, pixelCount - start);
        OCIO::PackedImageDesc img(rgb + 3 * start, long(n), 1, 3);
        cpu->apply(img);
    }
}

}  // namespace

std::string ColorManager::shippedConfigPath() { return sourcePath("spectral/ocio/config.ocio"); }

ColorManager::ColorManager(const std::string& configPath) {
    auto impl = std::make_shared<Impl>();
    if (!configPath.empty()) {
        impl->path = configPath;
    } else if (const char* env = std::getenv("OCIO"); env && *env) {
        impl->path = env;
    } else {
        impl->path = shippedConfigPath();
    }
    std::error_code ec;  // a path the file system refuses (too long) is "not found", not an exception
    if (!std::filesystem::is_regular_file(impl->path, ec)) fail(impl->path, ": OpenColorIO config not found");
    try {
        impl->config = OCIO::Config::CreateFromFile(impl->path.c_str());
        impl->config->validate();
    } catch (const OCIO::Exception& e) {
        fail(impl->path, ": invalid OpenColorIO config: ", e.what());
    }
    impl_ = std::move(impl);
}

const std::string& ColorManager::configPath() const { return impl_->path; }

bool ColorManager::hasColorSpace(const std::string& name) const {
    return !name.empty() && impl_->config->getColorSpace(name.c_str()) != nullptr;
}

std::vector<std::string> ColorManager::colorSpaces() const {
    std::vector<std::string> names;
    const int n = impl_->config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL);
    for (int i = 0; i < n; ++i)
        names.emplace_back(
            impl_->config->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i));
    return names;
}

void ColorManager::convert(float* rgb, size_t pixelCount, const std::string& from, const std::string& to) const {
    for (const std::string* cs : {&from, &to})
        if (!hasColorSpace(*cs)) fail(impl_->path, ": unknown colour space '", *cs, "'");
    OCIO::ConstProcessorRcPtr proc;
    try {
        proc = impl_->config->getProcessor(from.c_str(), to.c_str());
    } catch (const OCIO::Exception& e) {
        fail(impl_->path, ": cannot convert '", from, "' to '", to, "': ", e.what());
    }
    applyProcessor(proc, rgb, pixelCount);
}

void ColorManager::toDisplay(float* rgb, size_t pixelCount, const std::string& from, const std::string& display,
                             const std::string& view) const {
    if (!hasColorSpace(from)) fail(impl_->path, ": unknown colour space '", from, "'");
    const OCIO::ConstConfigRcPtr& config = impl_->config;
    const std::string d = display.empty() ? std::string(config->getDefaultDisplay()) : display;
    bool displayFound = false;
    for (int i = 0; i < config->getNumDisplays(); ++i) displayFound |= d == config->getDisplay(i);
    if (!displayFound) fail(impl_->path, ": unknown display '", d, "'");
    const std::string v = view.empty() ? std::string(config->getDefaultView(d.c_str())) : view;
    bool viewFound = false;
    for (int i = 0; i < config->getNumViews(d.c_str()); ++i) viewFound |= v == config->getView(d.c_str(), i);
    if (!viewFound) fail(impl_->path, ": display '", d, "' has no view '", v, "'");

    OCIO::ConstProcessorRcPtr proc;
    try {
        OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
        t->setSrc(from.c_str());
        t->setDisplay(d.c_str());
        t->setView(v.c_str());
        proc = config->getProcessor(t, OCIO::TRANSFORM_DIR_FORWARD);
    } catch (const OCIO::Exception& e) {
        fail(impl_->path, ": cannot build display transform '", from, "' → ", d, "/", v, ": ", e.what());
    }
    applyProcessor(proc, rgb, pixelCount);
}

}  // namespace iris
