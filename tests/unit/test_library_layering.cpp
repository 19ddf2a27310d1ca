// The library depends on nothing above it (STYLE.md rule 15, issue 30 item 9): no file of
// src/core, src/gpu, src/passes or src/library includes the optional scene component's
// headers (penumbra/scene/, or src/scene's own) or a tool's (apps/). Reads the sources
// themselves, so a new include fails here even where it would still compile (the scene
// headers lie in the same include folder as the library's).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// What an `#include` line names after its opening < or ", or "" for any other line. (No
// std::regex: GCC 12 warns of an uninitialized std::function inside it at -O1, which the
// sanitizer build turns into an error.)
std::string included_path(const std::string& line) {
    size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos || line[at] != '#') return "";
    at = line.find_first_not_of(" \t", at + 1);
    if (at == std::string::npos || line.compare(at, 7, "include") != 0) return "";
    at = line.find_first_not_of(" \t", at + 7);
    if (at == std::string::npos || (line[at] != '<' && line[at] != '"')) return "";
    return line.substr(at + 1);
}

// The scene component's and the tools' headers.
bool is_forbidden(const std::string& path) {
    for (const char* prefix : {"penumbra/scene/", "scene/", "renderer/", "bench/", "compare/", "quality/", "present/",
                               "image/", "penumbra/view/"}) {
        if (path.rfind(prefix, 0) == 0) return true;
    }
    return false;
}

// Every `#include` line of the library's layers that names a forbidden header.
std::vector<std::string> forbidden_includes(const fs::path& source_dir) {
    std::vector<std::string> found;
    for (const char* layer : {"src/core", "src/gpu", "src/passes", "src/library"}) {
        for (const fs::directory_entry& entry : fs::recursive_directory_iterator(source_dir / layer)) {
            if (!entry.is_regular_file()) continue;
            std::ifstream file(entry.path());
            std::string line;
            for (int number = 1; std::getline(file, line); ++number) {
                if (is_forbidden(included_path(line))) {
                    found.push_back(fs::relative(entry.path(), source_dir).string() + ":" + std::to_string(number) +
                                    ": " + line);
                }
            }
        }
    }
    return found;
}

TEST(LibraryLayering, NoLibraryLayerIncludesTheSceneComponentOrATool) {
    const fs::path source_dir = PENUMBRA_SOURCE_DIR;
    ASSERT_TRUE(fs::is_directory(source_dir / "src/core")) << source_dir;
    const std::vector<std::string> found = forbidden_includes(source_dir);
    std::string listing;
    for (const std::string& include : found) listing += "\n  " + include;
    EXPECT_TRUE(found.empty()) << "the library includes headers above it:" << listing;
}

// The check itself: it sees a forbidden include where there is one (a copy of a layer with
// one added), so that the test above cannot pass by reading nothing.
TEST(LibraryLayering, TheCheckFindsAnAddedSceneInclude) {
    const fs::path root = fs::temp_directory_path() / ("penumbra_layering_" + std::to_string(::getpid()));
    fs::remove_all(root);
    for (const char* layer : {"src/core", "src/gpu", "src/passes", "src/library"}) fs::create_directories(root / layer);
    std::ofstream(root / "src/passes/added.hpp") << "#pragma once\n#include \"penumbra/scene/scene.hpp\"\n";
    std::ofstream(root / "src/core/fine.hpp") << "#pragma once\n// penumbra/scene/ in a comment is fine\n";
    const std::vector<std::string> found = forbidden_includes(root);
    fs::remove_all(root);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0], "src/passes/added.hpp:2: #include \"penumbra/scene/scene.hpp\"");
}

}  // namespace
}  // namespace penumbra
