// A fresh clone renders every scene it ships: each scene file under scenes/, experiments/scenes/
// and experiments/perf/scenes/ loads, and every file it names (meshes, maps, spectra, includes'
// data) lies inside the repository (scenes/DATA.md lists the shipped data and its provenance).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "core/properties.h"
#include "core/source_tree.h"
#include "core/xml/xml_parser.h"
#include "render/loader/scene_loader.h"

using namespace iris;
namespace fs = std::filesystem;

namespace {

/// Scene files (not include fragments: those have no <sensor> of their own and are read through
/// the scene that includes them) in the folders a user renders from.
std::vector<std::string> shippedScenes() {
    std::vector<std::string> out;
    for (const char* dir : {"scenes", "experiments/scenes", "experiments/perf/scenes"}) {
        for (const auto& e : fs::directory_iterator(sourcePath(dir)))
            if (e.path().extension() == ".xml") out.push_back(e.path().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Every "filename" string value in a Properties tree (nested objects and children included).
void collectFilenames(const Properties& p, std::set<std::string>& out) {
    for (const std::string& name : p.names()) {
        const Properties::Entry* e = p.find(name);
        if (const auto* s = std::get_if<std::string>(&e->value); s && name == "filename") out.insert(*s);
        if (const auto* nested = std::get_if<PropertiesPtr>(&e->value)) collectFilenames(**nested, out);
    }
    for (const PropertiesPtr& c : p.children()) collectFilenames(*c, out);
}

bool insideRepository(const std::string& path) {
    const std::string root = fs::weakly_canonical(sourceDir()).string() + "/";
    return fs::weakly_canonical(path).string().rfind(root, 0) == 0;
}

}  // namespace

TEST(ShippedScenes, EveryFileTheyNameIsInTheRepository) {
    const std::vector<std::string> scenes = shippedScenes();
    ASSERT_GE(scenes.size(), 10u) << "the scene folders moved?";
    for (const std::string& scene : scenes) {
        std::set<std::string> files;
        for (const PropertiesPtr& obj : parseSceneFile(scene).objects) collectFilenames(*obj, files);
        for (const std::string& f : files) {
            EXPECT_TRUE(insideRepository(f)) << scene << " names " << f << ", outside the repository";
            EXPECT_TRUE(fs::exists(f)) << scene << " names " << f << ", which does not exist";
        }
    }
}

TEST(ShippedScenes, EveryOneLoads) {
    for (const std::string& scene : shippedScenes()) {
        SCOPED_TRACE(scene);
        EXPECT_NO_THROW(loadScene(scene)) << scene;
    }
}

TEST(ShippedScenes, TheRepositoryCheckRejectsAPathOutsideIt) {
    // The check above can fail: ../shared, where these files used to live, is outside.
    EXPECT_FALSE(insideRepository(sourcePath("../shared/data/meshes/dragon.ply")));
    EXPECT_TRUE(insideRepository(sourcePath("scenes/meshes/dragon.ply")));
}
