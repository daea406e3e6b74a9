// Writes a Mitsuba `.vol` grid (version 3, float32, the given bounding box; core/io/vol_reader.h) into a
// per-test temporary folder (ctest may run tests in parallel processes) and returns its path.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris::test {

inline std::string writeVolFile(const std::string& folder, const std::string& name, ivec3 res, int channels,
                                const std::vector<float>& v, vec3 bmin = vec3(0.0f), vec3 bmax = vec3(1.0f)) {
    std::string s = "VOL";
    s.push_back(3);
    auto i32 = [&](int32_t x) {
        for (int i = 0; i < 4; ++i) s.push_back(char(uint32_t(x) >> (8 * i) & 0xff));
    };
    auto f32 = [&](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        i32(int32_t(u));
    };
    for (int32_t x : {1, res.x, res.y, res.z, channels}) i32(x);
    for (int a = 0; a < 3; ++a) f32(bmin[a]);
    for (int a = 0; a < 3; ++a) f32(bmax[a]);
    for (float f : v) f32(f);
    const auto dir = std::filesystem::temp_directory_path() /
                     (folder + "_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary).write(s.data(), std::streamsize(s.size()));
    return path;
}

}  // namespace iris::test
