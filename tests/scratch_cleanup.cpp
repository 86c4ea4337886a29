// Linked into every test executable (lobe_gtest, cmake/LobeHelpers.cmake): removes the scratch
// files and folders the process's tests made in the system temp folder, once they have all
// passed. Tests name their scratch "lobe_..._<pid>" or "lobe_..._<pid>.<ext>" (temp_dir() in
// tests/run_command.h and the suites' own helpers), so a process finds its own by its id; when a
// test failed, they are kept to look at, and named on stderr. (ctest runs each test in a process
// of its own, so one failure keeps only that test's scratch.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

// `name` is "lobe_" ... "_<pid>", possibly followed by an extension.
bool made_by_this_process(const std::string& name, const std::string& pid_tag) {
  if (name.rfind("lobe_", 0) != 0) return false;
  for (size_t at = name.find(pid_tag); at != std::string::npos; at = name.find(pid_tag, at + 1)) {
    size_t end = at + pid_tag.size();
    if (end == name.size() || name[end] == '.') return true;
  }
  return false;
}

class ScratchCleanup : public ::testing::Environment {
public:
  void TearDown() override {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path tmp = fs::temp_directory_path(ec);
    if (ec) return;
    std::string tag = "_"; // (not "_" + to_string(): GCC 12 warns falsely of an overlap)
    tag += std::to_string(::getpid());
    const bool passed = ::testing::UnitTest::GetInstance()->Passed();
    std::vector<fs::path> ours;
    for (fs::directory_iterator it(tmp, ec), end; !ec && it != end; it.increment(ec))
      if (made_by_this_process(it->path().filename().string(), tag)) ours.push_back(it->path());
    for (const fs::path& p : ours) {
      if (!passed) {
        std::cerr << "scratch kept (a test failed): " << p.string() << "\n";
        continue;
      }
      std::error_code rm;
      fs::remove_all(p, rm);
    }
  }
};

[[maybe_unused]] ::testing::Environment* const kScratchCleanup =
    ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

} // namespace
