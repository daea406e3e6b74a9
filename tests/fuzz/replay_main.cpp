// A main() for the fuzz targets in the normal build (without libFuzzer): it replays every file
// named on the command line, or found (sorted) in a folder named there, through the target's
// LLVMFuzzerTestOneInput. CTest runs it on tests/fuzz/corpus/<target> so that every committed
// seed and every input that once crashed stays handled. Options starting with '-' (libFuzzer's,
// e.g. -runs=0) are ignored, so the same command line works for the libFuzzer build.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

std::vector<std::filesystem::path> inputsOf(const std::filesystem::path& arg) {
    if (!std::filesystem::is_directory(arg)) return {arg};
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

int main(int argc, char** argv) {
    size_t replayed = 0;
    for (int i = 1; i < argc; ++i) {
        if (argv[i][0] == '-') continue;
        for (const auto& file : inputsOf(argv[i])) {
            std::ifstream f(file, std::ios::binary);
            if (!f) {
                std::fprintf(stderr, "%s: cannot read\n", file.c_str());
                return 1;
            }
            const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
            LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
            ++replayed;
        }
    }
    std::printf("replayed %zu inputs\n", replayed);
    // An empty or missing corpus would make the test vacuous.
    return replayed > 0 ? 0 : 1;
}
