// Every test process writes its temporary files into a folder of its own, removed when the
// process's tests end: a GoogleTest global environment creates $TMPDIR/iris-tests-XXXXXX, points
// TMPDIR at it (std::filesystem::temp_directory_path, core/io/output_file.h's temporaryFolder and
// the rendered apps all read TMPDIR) and removes it afterwards. Without it each ctest run left about
// 140 files and folders in /tmp (per-process names such as iris_hostile_<pid>), a GiB after a few
// hundred runs. A process that crashes keeps its folder, which is then the evidence.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace {

class ScratchTmpdir : public ::testing::Environment {
public:
    void SetUp() override {
        const char* old = std::getenv("TMPDIR");
        if (old) saved_ = old;
        std::string tmpl = std::string(old && *old ? old : "/tmp") + "/iris-tests-XXXXXX";
        if (!::mkdtemp(tmpl.data())) return;  // an unusable TMPDIR: the tests see it as it is
        dir_ = tmpl;
        ::setenv("TMPDIR", dir_.c_str(), 1);
    }
    void TearDown() override {
        if (dir_.empty()) return;
        saved_ ? ::setenv("TMPDIR", saved_->c_str(), 1) : ::unsetenv("TMPDIR");
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }

private:
    std::optional<std::string> saved_;
    std::string dir_;
};

const ::testing::Environment* const kScratch = ::testing::AddGlobalTestEnvironment(new ScratchTmpdir);

}  // namespace
