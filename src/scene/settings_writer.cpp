#include "penumbra/scene/setting_presentation.hpp"
#include "penumbra/scene/settings_files.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "penumbra/errors.hpp"
#include "penumbra/settings.hpp"

namespace penumbra {
namespace {

// 9 significant digits: the shortest precision at which every float survives
// float -> decimal -> double -> float unchanged.
std::string real(float value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(value));
    std::string result(text);
    // TOML needs a decimal point or exponent for a float; an integer-looking value is fine
    // (the reader accepts integers where numbers are expected) but "1.0" reads better.
    if (result.find_first_of(".eEn") == std::string::npos) result += ".0";
    return result;
}

std::string vec3(const glm::vec3& value) {
    return "[" + real(value.x) + ", " + real(value.y) + ", " + real(value.z) + "]";
}

std::string boolean(bool value) { return value ? "true" : "false"; }

// One [shadow] key as TOML writes it; manual splits only when there are any. (A stream:
// GCC 12 at -O3 warns falsely, -Wrestrict, about "literal" + std::string chains.)
void write_setting(std::ostream& out, const SettingDeclaration& setting, const SettingValue& value) {
    const std::vector<float>* list = std::get_if<std::vector<float>>(&value);
    if (list && list->empty()) return;
    out << presentation_of(setting).key_in_config() << " = ";
    if (const bool* flag = std::get_if<bool>(&value)) out << boolean(*flag);
    if (const int64_t* integer = std::get_if<int64_t>(&value)) out << *integer;
    if (const double* number = std::get_if<double>(&value)) out << real(static_cast<float>(*number));
    if (const std::string* name = std::get_if<std::string>(&value)) out << '"' << *name << '"';
    if (list) {
        out << '[';
        for (size_t i = 0; i < list->size(); ++i) out << (i ? ", " : "") << real((*list)[i]);
        out << ']';
    }
    out << '\n';
}

}  // namespace

std::string format_settings_file(const RenderSettings& settings, const Camera& camera, const Light* sun) {
    std::ostringstream out;
    out << "# Written by penumbra view; `penumbra render SCENE --config THIS_FILE` reproduces the view.\n";
    out << "[output]\n";
    for (const SettingDeclaration& setting : kOutputSettingDeclarations)
        write_setting(out, setting, setting.get(settings));
    out << "\n[shadow]\n";
    for (const SettingDeclaration& setting : kSettingDeclarations) write_setting(out, setting, setting.get(settings));
    out << "\n[camera]\neye = " << vec3(camera.eye) << "\ntarget = " << vec3(camera.target)
        << "\nup = " << vec3(camera.up) << "\nfov = " << real(camera.fov_y_degrees)
        << "\nnear = " << real(camera.near_plane) << "\nfar = " << real(camera.far_plane) << "\n";
    if (sun) {
        out << "\n[sun]\ndirection = " << vec3(sun->direction)
            << "\nangular_diameter = " << real(sun->angular_diameter_degrees) << "\n";
    }
    return out.str();
}

void write_settings_file(const std::filesystem::path& path, const RenderSettings& settings, const Camera& camera,
                         const Light* sun) {
    const std::string text = format_settings_file(settings, camera, sun);
    const std::filesystem::path temporary = path.string() + ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        file << text;
        if (!file.good()) throw InputError(path.string() + ": cannot write the settings file");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw InputError(path.string() + ": cannot write the settings file");
    }
}

}  // namespace penumbra
