// libFuzzer harness: glTF models, .gltf (text) or .glb (binary) as FUZZ_GLTF_EXTENSION says.
// The input is written to a file in a private folder (the loader reads files, and resolves
// uris against that folder) and loaded into a scene: a scene or one InputError, nothing else.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"

namespace {

const std::filesystem::path& model_path() {
    static const std::filesystem::path path = [] {
        const std::filesystem::path folder =
            std::filesystem::temp_directory_path() / ("penumbra-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::create_directories(folder);
        return folder / (std::string("model") + FUZZ_GLTF_EXTENSION);
    }();
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    {
        std::ofstream file(model_path(), std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        penumbra::Scene scene;
        penumbra::append_gltf(scene, model_path(), {glm::mat4{1.0f}, glm::mat4{2.0f}});
    } catch (const penumbra::InputError&) {
    }
    return 0;
}
