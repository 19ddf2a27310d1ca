// The files a glTF names by uri, checked before tinygltf opens them so that what is refused
// is said plainly. glTF 2.0 (section 3.9.2, "URIs"): a uri is either a data: URI or a
// reference relative to the glTF file. Left to itself, tinygltf joins an absolute path to the
// model's folder and reports "File not found" for a file that exists, falls back to the
// current directory when the file is not beside the model, and reports the byte size of
// whatever file a `../` path reaches. Here, a uri with a scheme or an absolute path is
// refused naming that reason, a file is looked for in the model's folder only, and a buffer
// whose file has the wrong size is refused without saying the size it has.
#include <cctype>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// "scheme:" before any '/' (RFC 3986: a letter, then letters, digits, '+', '-' or '.').
bool has_scheme(const std::string& uri) {
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
    for (const char c : uri) {
        if (c == ':') return true;
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
    }
    return false;
}

}  // namespace

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string decode_gltf_uri(const std::string& uri, const std::string& origin, const std::string& where) {
    std::string path;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%') {
            const int high = i + 2 < uri.size() ? hex_digit(uri[i + 1]) : -1;
            const int low = high >= 0 ? hex_digit(uri[i + 2]) : -1;
            if (low < 0) throw InputError(origin + ": " + where + ": malformed percent-encoding in \"" + uri + "\"");
            path += static_cast<char>(high * 16 + low);
            i += 2;
        } else {
            path += uri[i] == '+' ? ' ' : uri[i];  // as tinygltf decodes it (dlib's urldecode)
        }
    }
    return path;
}

void check_gltf_uri(const GltfUri& uri, const std::string& origin) {
    if (is_data_uri(uri.text)) return;  // tinygltf decodes it and names what is wrong with it
    const std::string at = origin + ": " + uri.where + " \"" + uri.text + "\": ";
    if (uri.text.empty()) throw InputError(origin + ": " + uri.where + ": the uri is empty");
    if (has_scheme(uri.text)) {
        throw InputError(at + "a URI with a scheme; Penumbra reads data: URIs and files named relative to the model");
    }
    const std::string path = decode_gltf_uri(uri.text, origin, uri.where);
    for (const char c : path) {
        if (static_cast<unsigned char>(c) < 0x20) throw InputError(at + "the path holds a control character");
    }
    if (path.front() == '/') {
        throw InputError(at + "an absolute path; glTF uris name files relative to the model's folder");
    }
    if (!uri.byte_length) return;  // images: checked when a material uses them (gltf_primitive.cpp)
    const fs::path file = uri.folder / path;
    std::error_code error;
    if (!fs::exists(file, error)) throw InputError(at + "no such file relative to the model's folder");
    if (!fs::is_regular_file(file, error)) throw InputError(at + "not a regular file");
    if (fs::file_size(file, error) != *uri.byte_length || error) {
        throw InputError(at + "the file is not the buffer's byteLength (" + std::to_string(*uri.byte_length) +
                         " bytes) long");
    }
}

}  // namespace penumbra
