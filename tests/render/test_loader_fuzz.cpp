// Fixed-seed mutation fuzzing of the scene loader and mesh readers: every mutated input must either
// load or throw iris::Error (never crash, hang, or throw anything else). Bounded: a few thousand
// small inputs, well under the test time budget.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <cstdlib>

#include "core/error.h"
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "render/loader/scene_loader.h"

namespace fs = std::filesystem;
using namespace iris;

namespace {

fs::path fuzzDir() {
    const fs::path d = fs::temp_directory_path() / ("iris_fuzz_tests_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

void writeFile(const std::string& rel, const std::string& s) { std::ofstream(fuzzDir() / rel, std::ios::binary) << s; }

const char* kSeedScene = R"(<scene version="3.0.0">
    <default name="spp" value="4"/>
    <default name="res" value="32"/>
    <path value="."/>
    <include filename="part.xml"/>
    <integrator type="path">
        <integer name="max_depth" value="5"/>
        <boolean name="hide_emitters" value="false"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <string name="fov_axis" value="smaller"/>
        <transform name="to_world">
            <lookat origin="0, 1, -5" target="0, 1, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/>
            <integer name="height" value="$res"/>
            <rfilter type="gaussian"><float name="stddev" value="0.5"/></rfilter>
        </film>
    </sensor>
    <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
    <texture type="checkerboard" id="checks">
        <rgb name="color0" value="0.4"/><srgb name="color1" value="#336699"/>
        <transform name="to_uv"><scale x="4" y="4"/></transform>
    </texture>
    <emitter type="area" id="lamp"><blackbody name="radiance" temperature="3000" scale="2"/></emitter>
    <shape type="obj" id="tri">
        <string name="filename" value="tri.obj"/>
        <transform name="to_world">
            <translate x="1" y="2" z="3"/>
            <rotate y="1" angle="30"/>
            <scale value="2"/>
            <matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>
        </transform>
        <ref id="white"/>
    </shape>
    <shape type="ply"><string name="filename" value="quad.ply"/><ref id="lamp"/></shape>
    <shape type="rectangle"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf>
        <boolean name="flip_normals" value="true"/></shape>
    <shape type="sphere"><point name="center" x="0" y="1" z="0"/><float name="radius" value="0.5"/>
        <emitter type="area"><spectrum name="radiance" value="400:1, 500:2, 700:3"/></emitter></shape>
    <shape type="cube"/>
    <shape type="disk"><transform name="to_world"><rotate value="1 0 0" angle="90"/></transform></shape>
    <shape type="shapegroup" id="grp"><shape type="cube"><ref id="white"/></shape>
        <shape type="sphere"><float name="radius" value="0.3"/></shape></shape>
    <shape type="instance"><ref id="grp"/><transform name="to_world"><scale x="2" y="0.5" z="1"/></transform></shape>
</scene>
)";

const char* kSeedPart = R"(<scene version="0.6.0">
    <bsdf type="diffuse" id="grey"><spectrum name="reflectance" value="0.5"/></bsdf>
    <shape type="sphere"><transform name="toWorld"><translate x="-1"/></transform><ref id="grey"/></shape>
</scene>
)";

const char* kTriObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf -1 -2 -3\n";
const char* kQuadPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

const char* kTokens[] = {"",    "-1",   "0",     "1e40", "nan",  "inf", "$spp", "$nope", "abc", "99999999999",
                         "1 2", "#zz",  "400:1", ":",    "true", "3.0.0", "0.6.0", "part.xml", "tri.obj",
                         "quad.ply", "-0", "1,2,3,4", "white", "lamp", "checks", "<", "&amp;", "65536",
                         "grp", "shapegroup", "instance"};

std::vector<std::string> splitLines(const std::string& s) {
    std::vector<std::string> lines;
    size_t b = 0;
    while (b <= s.size()) {
        const size_t e = s.find('\n', b);
        lines.push_back(s.substr(b, e == std::string::npos ? std::string::npos : e - b));
        if (e == std::string::npos) break;
        b = e + 1;
    }
    return lines;
}

std::string joinLines(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + '\n';
    return s;
}

/// One random mutation: flip/insert/delete bytes, delete/duplicate/swap lines, or replace an
/// attribute value by a nasty token.
std::string mutate(std::string s, std::mt19937& rng) {
    if (s.empty()) return s;
    auto pick = [&](size_t n) { return size_t(rng() % std::max<size_t>(n, 1)); };
    switch (rng() % 7) {
        case 0: s[pick(s.size())] = char(rng() & 0xFF); break;
        case 1: s.insert(pick(s.size()), 1, "<>\"/=$ x0\n"[pick(10)]); break;
        case 2: {
            const size_t at = pick(s.size());
            s.erase(at, pick(16) + 1);
            break;
        }
        case 3: case 4: {
            auto lines = splitLines(s);
            const size_t i = pick(lines.size()), j = pick(lines.size());
            if (rng() % 3 == 0) lines.erase(lines.begin() + long(i));
            else if (rng() % 2) lines.insert(lines.begin() + long(i), lines[j]);
            else std::swap(lines[i], lines[j]);
            s = joinLines(lines);
            break;
        }
        default: {
            // Replace the n-th quoted attribute value.
            std::vector<size_t> quotes;
            for (size_t i = 0; i < s.size(); ++i)
                if (s[i] == '"') quotes.push_back(i);
            if (quotes.size() < 2) break;
            const size_t q = pick(quotes.size() / 2) * 2;
            const size_t b = quotes[q] + 1, e = quotes[q + 1];
            s.replace(b, e - b, kTokens[pick(std::size(kTokens))]);
        }
    }
    return s;
}

/// Run f; anything but success or iris::Error fails the test.
template <typename F>
bool survives(F&& f, const std::string& input) {
    try {
        f();
        return true;
    } catch (const Error&) {
        return false;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "non-iris exception: " << e.what() << "\ninput:\n" << input;
        return false;
    }
}

}  // namespace

TEST(LoaderFuzz, SceneMutationsLoadOrThrowIrisError) {
    writeFile("part.xml", kSeedPart);
    writeFile("tri.obj", kTriObj);
    writeFile("quad.ply", kQuadPly);
    const std::string base = fuzzDir().string();
    ASSERT_NO_THROW(loadSceneFromString(kSeedScene, base)) << "the seed scene must load";
    // IRIS_FUZZ_ITERATIONS / IRIS_FUZZ_SEED allow longer runs by hand (e.g. under sanitizers).
    const char* itEnv = std::getenv("IRIS_FUZZ_ITERATIONS");
    const char* seedEnv = std::getenv("IRIS_FUZZ_SEED");
    std::mt19937 rng(seedEnv ? uint32_t(std::strtoul(seedEnv, nullptr, 10)) : 20261122u);
    int loaded = 0;
    const int kIterations = itEnv ? std::max(10, std::atoi(itEnv)) : 2000;
    for (int it = 0; it < kIterations; ++it) {
        std::string xml = kSeedScene;
        const int n = 1 + int(rng() % 3);
        for (int k = 0; k < n; ++k) xml = mutate(xml, rng);
        loaded += survives([&] { loadSceneFromString(xml, base); }, xml);
        // Every 10th iteration also mutates the included file and reloads.
        if (it % 10 == 0) {
            writeFile("part.xml", mutate(kSeedPart, rng));
            survives([&] { loadSceneFromString(kSeedScene, base); }, kSeedScene);
            writeFile("part.xml", kSeedPart);
        }
    }
    // Sanity: the mutations are neither all harmless nor all fatal.
    EXPECT_GT(loaded, kIterations / 20);
    EXPECT_LT(loaded, kIterations);
}

TEST(LoaderFuzz, MeshMutationsParseOrThrowIrisError) {
    std::mt19937 rng(7);
    for (int it = 0; it < 1500; ++it) {
        std::string obj = kTriObj, ply = kQuadPly;
        const int n = 1 + int(rng() % 3);
        for (int k = 0; k < n; ++k) {
            obj = mutate(obj, rng);
            ply = mutate(ply, rng);
        }
        survives([&] { parseObj(obj, "fuzz.obj"); }, obj);
        survives([&] { parsePly(ply, "fuzz.ply"); }, ply);
    }
}
