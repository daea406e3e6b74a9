// libFuzzer target: Mitsuba XML scenes through loadSceneFromString (parsing, includes, <default>s
// and $-substitution, <ref>s, 0.6 upgrades, then every plugin's parameter checks). The scene's
// folder holds a small fixed set of files the seeds refer to: part.xml (an include), tri.obj and
// tri.ply (meshes), flat.spd (a spectrum), tex.png and env.exr (images, read by the bitmap texture
// and the envmap through readImage, as the renderer reads them), and the hostile names of issue 38:
// zero (a symbolic link to /dev/zero), fifo (a FIFO nobody writes to) and dir (a folder), so that
// the checks of core/input_file.h are fuzzed wherever a scene names a file. A regression there hangs
// (libFuzzer's -timeout reports it) or grows a buffer past -rss_limit_mb.
#include <sys/stat.h>

#include <filesystem>

#include "core/io/image.h"
#include "render/loader/scene_loader.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void writeText(const std::string& name, const std::string& text) {
    iris::fuzz::writeInput(reinterpret_cast<const uint8_t*>(text.data()), text.size(), name);
}

const std::string& sceneDir() {
    static const std::string dir = [] {
        writeText("part.xml", "<scene version=\"3.0.0\">\n  <bsdf type=\"diffuse\" id=\"inc\"/>\n</scene>\n");
        writeText("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
        writeText("tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        writeText("flat.spd", "400 0.5\n700 0.5\n");
        const std::filesystem::path dir = iris::fuzz::scratchDir();
        iris::Image img(8, 4, 3);
        for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i % 7) / 7.0f;
        iris::writeEXR((dir / "env.exr").string(), img);
        iris::writeLDR((dir / "tex.png").string(), img);
        std::error_code ec;
        std::filesystem::create_symlink("/dev/zero", dir / "zero", ec);
        ::mkfifo((dir / "fifo").c_str(), 0644);
        std::filesystem::create_directories(dir / "dir");
        return dir.string();
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string xml(reinterpret_cast<const char*>(data), size);
    iris::fuzz::expectResultOrIrisError([&] { iris::loadSceneFromString(xml, sceneDir()); });
    return 0;
}
