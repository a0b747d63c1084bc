// What the vds tool's tests share: a temporary directory per test, the tool
// run in it, and the files they write and read there.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include <vds/mesh.h>

#include "../support/run_program.h"

namespace vds::test {

/// `mesh` as an OBJ file, with enough digits that every float reads back as itself.
inline void writeObj(const std::filesystem::path& path, const vds::TriangleMesh& mesh) {
    std::ofstream out(path);
    out.precision(9);
    for (const auto& v : mesh.positions) out << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    for (const auto& t : mesh.triangles) out << "f " << t.x + 1 << ' ' << t.y + 1 << ' ' << t.z + 1 << '\n';
}

inline std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A test with a directory of its own (named by `prefix`, the process and
/// the test), removed afterwards, and the tool run on paths in it.
class ToolDirectory : public ::testing::Test {
protected:
    explicit ToolDirectory(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() /
              (prefix_ + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string p(const std::string& name) const { return (dir / name).string(); }
    Result vds(const std::string& args) const { return run(std::string(VDS_TOOL) + " " + args); }
    std::filesystem::path dir;

private:
    std::string prefix_;
};

} // namespace vds::test
