// libFuzzer harness: scene files (TOML). Any input must parse into a scene or throw one
// InputError; nothing else (a crash, a hang, a sanitizer report, another exception).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "penumbra/errors.hpp"
#include "penumbra/scene/loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        // glTF objects resolve against the corpus folder: a seed may name a fixture there.
        penumbra::parse_scene_toml(text, "fuzz.toml", PENUMBRA_FUZZ_DATA_DIR);
    } catch (const penumbra::InputError&) {
    }
    return 0;
}
