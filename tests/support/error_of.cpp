#include "tests/support/error_of.h"

#include "render/loader/scene_loader.h"

namespace iris::test {

std::string sceneError(const std::string& body, const std::string& version) {
    return errorOf([&] { loadSceneFromString("<scene version=\"" + version + "\">\n" + body + "</scene>\n", "."); });
}

}  // namespace iris::test
