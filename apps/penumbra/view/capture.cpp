#include "capture.hpp"

#include "image/png_io.hpp"

namespace penumbra::view {

void write_capture(const Capture& capture) {
    switch (capture.aov) {
        case Aov::None:
            write_png_rgba8(capture.file, capture.width, capture.height, capture.rgba);
            break;
        case Aov::Shadow:
        case Aov::Contact:  // not offered by the viewer; written as render writes it
            write_png_gray16(capture.file, capture.width, capture.height, capture.visibility);
            break;
        case Aov::Cascade:
            write_png_gray8(capture.file, capture.width, capture.height, capture.cascade);
            break;
    }
}

}  // namespace penumbra::view
