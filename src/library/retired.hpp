#pragma once
// Objects the GPU may still be using: a ShadowSystem keeps what it replaces or removes
// until the frames that could have used it are complete. With F frames in flight,
// prepare() of frame M guarantees that frame M - F has completed, so an object retired
// during frame R may be destroyed from frame R + F on.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace penumbra::library {

class RetiredObjects {
public:
    explicit RetiredObjects(uint32_t frames_in_flight) : frames_in_flight_(frames_in_flight) {}

    // Keeps `object` alive until frame `current_frame` + frames in flight.
    template <typename T>
    void retire(T object, uint64_t current_frame) {
        entries_.push_back({current_frame, std::make_unique<Holder<T>>(std::move(object))});
    }

    // Destroys what frame `starting_frame` may no longer use.
    void release(uint64_t starting_frame) {
        std::erase_if(entries_,
                      [&](const Entry& entry) { return entry.retired_frame + frames_in_flight_ <= starting_frame; });
    }

    size_t size() const { return entries_.size(); }

private:
    struct Object {
        virtual ~Object() = default;
    };
    template <typename T>
    struct Holder : Object {
        explicit Holder(T value) : held(std::move(value)) {}
        T held;
    };
    struct Entry {
        uint64_t retired_frame;
        std::unique_ptr<Object> object;
    };

    uint32_t frames_in_flight_;
    std::vector<Entry> entries_;
};

}  // namespace penumbra::library
