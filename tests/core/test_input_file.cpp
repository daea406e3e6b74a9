// The checks every named input file goes through (core/input_file.h, issue 38): a regular file is
// read whole; a device, a FIFO, a socket, a directory or a missing file is refused with its kind
// named before any byte is read (a regression would hang on the FIFO or grow a buffer without end
// on /dev/zero: CTest's per-test timeout stops it); a file over its format's limit or the memory
// budget is refused before its buffer exists; and every reader the renderer uses (images, spectra,
// scene includes, meshes, volume grids, checkpoints) goes through them.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "core/error.h"
#include "core/input_file.h"
#include "core/io/image.h"
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/vol_reader.h"
#include "core/memory_budget.h"
#include "core/xml/xml_parser.h"
#include "render/film.h"
#include "spectral/spectrum_factory.h"
#include "tests/support/app_runner.h"
#include "tests/support/error_of.h"
#include "tests/support/hostile_files.h"

using namespace iris;
using iris::testing::tempPath;

namespace {

/// A Unix-domain socket bound at `path` (closed on destruction; the file stays until removed).
struct BoundSocket {
    int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    explicit BoundSocket(const std::string& path) {
        std::remove(path.c_str());
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, path.c_str(), sizeof(a.sun_path) - 1);
        EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0) << path;
    }
    ~BoundSocket() { ::close(fd); }
};

/// The non-regular inputs every reader must refuse, each with the words its message must hold.
struct Hostile {
    std::string path, kind;
};

std::vector<Hostile> hostileInputs() {
    const std::string dir = tempPath("input_file", "dir");
    std::filesystem::create_directories(dir);
    const std::string link = tempPath("input_file", "zero_link.exr");
    std::remove(link.c_str());
    std::filesystem::create_symlink("/dev/zero", link);
    return {{"/dev/zero", "a character device"},
            {"/dev/urandom", "a character device"},
            {link, "a character device"},  // a symbolic link is followed to what it names
            {iris::testing::makeFifo(tempPath("input_file", "fifo")), "a FIFO (named pipe)"},
            {dir, "a directory"},
            {tempPath("input_file", "missing"), "file not found"}};
}

}  // namespace

TEST(InputFile, ARegularFileIsReadWholeAndItsSizeReported) {
    const std::string path = tempPath("input_file", "plain.txt");
    iris::testing::writeTextFile(path, "0123456789");
    EXPECT_EQ(readInputFile(path, "text file"), "0123456789");
    EXPECT_EQ(checkInputFile(path, "text file"), 10u);
    EXPECT_EQ(readInputFile(path, "text file", 10), "0123456789");  // exactly at the limit
}

TEST(InputFile, DevicesFifosSocketsDirectoriesAndMissingFilesAreRefusedWithTheirKind) {
    const BoundSocket socket(tempPath("input_file", "sock"));
    std::vector<Hostile> inputs = hostileInputs();
    inputs.push_back({tempPath("input_file", "sock"), "a socket"});
    for (const Hostile& h : inputs) {
        for (const std::string& e : {test::errorOf([&] { readInputFile(h.path, "spectrum file"); }),
                                     test::errorOf([&] { checkInputFile(h.path, "image"); })}) {
            EXPECT_EQ(e.rfind(h.path + ": cannot open ", 0), 0u) << e;
            EXPECT_NE(e.find(h.kind), std::string::npos) << e;
        }
    }
}

TEST(InputFile, AFileOverItsFormatLimitOrTheBudgetIsRefusedBeforeReading) {
    const std::string path = tempPath("input_file", "eleven.txt");
    iris::testing::writeTextFile(path, "01234567890");
    const std::string e = test::errorOf([&] { readInputFile(path, "spectrum file", 10); });
    EXPECT_NE(e.find(path + ": spectrum file of 11 B exceeds the limit of 10 B for a spectrum file"), std::string::npos) << e;
    const uint64_t before = memoryLimit();
    setMemoryLimit(memoryCharged() + 10);
    const std::string budget = test::errorOf([&] { readInputFile(path, "PLY file"); });
    setMemoryLimit(before);
    EXPECT_NE(budget.find(path + ": reading the PLY file needs 11 B, over the memory limit"), std::string::npos) << budget;
}

// Every reader of a named file refuses every hostile input with the checks' message.
TEST(InputFile, EveryReaderOfANamedFileGoesThroughTheChecks) {
    const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> readers = {
        {"image", [](const std::string& p) { readImage(p); }},
        {"image", [](const std::string& p) { readEXRMetadata(p); }},
        {"spectrum file", [](const std::string& p) { loadSpdFile(p, SpectrumKind::Reflectance); }},
        {"scene file", [](const std::string& p) { parseSceneFile(p); }},
        {"PLY file", [](const std::string& p) { readPly(p); }},
        {"OBJ file", [](const std::string& p) { readObj(p); }},
        {".vol grid file", [](const std::string& p) { readVolFile(p); }},
        {"checkpoint", [](const std::string& p) {
             std::string header;
             Film::read(p, &header);
         }},
    };
    for (const Hostile& h : hostileInputs())
        for (const auto& [kind, read] : readers) {
            const std::string e = test::errorOf([&] { read(h.path); });
            EXPECT_NE(e.find(h.path + ": cannot open " + kind), std::string::npos) << e;
            EXPECT_NE(e.find(h.kind), std::string::npos) << e;
        }
}

// A scene that includes /dev/zero, or a folder, names the include's line.
TEST(InputFile, AnIncludeOfADeviceNamesItsLine) {
    const std::string e = test::errorOf(
        [] { parseSceneString("<scene version=\"3.0.0\">\n<include filename=\"/dev/zero\"/>\n</scene>", "."); });
    EXPECT_EQ(e, "<string>:2: /dev/zero: cannot open included file: it is a character device, not a regular file");
    const std::string folder = test::errorOf([] { parseSceneString("<scene version=\"3.0.0\">\n<include filename=\"/tmp\"/>\n</scene>", "."); });
    EXPECT_EQ(folder, "<string>:2: '/tmp' is a directory, not a file (/tmp)");
}
