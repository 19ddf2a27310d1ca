// The values tinygltf reads without checking their type or range: a property of the wrong
// JSON type is skipped as if absent (`"translation": ["1", 0, 0]` leaves the node where it
// was, `"doubleSided": "yes"` keeps back faces culled) and numbers outside the range the
// glTF 2.0 specification gives them are used as they are (`"alphaCutoff": -5` keeps every
// texel). Both are errors naming the JSON path, checked on the JSON before tinygltf reads
// it; the ranges are the specification's (glTF 2.0, section 5, and the KHR_lights_punctual,
// KHR_materials_emissive_strength and KHR_texture_transform extensions).
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "penumbra/errors.hpp"
#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

using Json = nlohmann::json;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kHalfPi = 1.57079632679489661923;

// A closed or half-open range of numbers, as the specification states it.
struct Range {
    double minimum = -kInfinity;
    double maximum = kInfinity;
    bool exclusive_minimum = false;
    bool exclusive_maximum = false;

    bool holds(double value) const {
        return (exclusive_minimum ? value > minimum : value >= minimum) &&
               (exclusive_maximum ? value < maximum : value <= maximum);
    }
    std::string text() const {
        const auto number = [](double value) { return Json(value).dump(); };
        if (minimum == -kInfinity && maximum == kInfinity) return "a number";
        if (maximum == kInfinity)
            return std::string("a number ") + (exclusive_minimum ? "> " : ">= ") + number(minimum);
        return std::string("a number in ") + (exclusive_minimum ? "(" : "[") + number(minimum) + ", " +
               number(maximum) + (exclusive_maximum ? ")" : "]");
    }
};

constexpr Range kAnyNumber{};
constexpr Range kUnit{0.0, 1.0};
constexpr Range kNonNegative{0.0};
constexpr Range kPositive{0.0, kInfinity, true};
constexpr Range kSigned{-1.0, 1.0};

class ValueChecker {
public:
    explicit ValueChecker(const std::string& origin) : origin_(origin) {}

    [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
        throw InputError(origin_ + ": " + where + ": " + problem);
    }

    // The member `key` of `object`, or nullptr when `object` is not an object or lacks it.
    static const Json* member(const Json& object, const char* key) {
        if (!object.is_object()) return nullptr;
        const auto found = object.find(key);
        return found == object.end() ? nullptr : &*found;
    }

    // An optional number within `range`.
    void number(const Json& object, const char* key, const std::string& where, const Range& range) const {
        if (const Json* value = member(object, key)) number_value(*value, where + "." + key, range);
    }

    // An optional array of exactly `size` numbers (any number of them: kAnyLength), each
    // within `range`.
    static constexpr size_t kAnyLength = std::numeric_limits<size_t>::max();
    void numbers(const Json& object, const char* key, const std::string& where, size_t size, const Range& range) const {
        const Json* value = member(object, key);
        if (!value) return;
        const std::string at = where + "." + key;
        if (!value->is_array() || (size != kAnyLength && value->size() != size)) {
            const std::string count = size == kAnyLength ? "" : std::to_string(size) + " ";
            fail(at, "expected an array of " + count + "numbers, got " + value->dump());
        }
        for (size_t i = 0; i < value->size(); ++i) {
            number_value((*value)[i], at + "[" + std::to_string(i) + "]", range);
        }
    }

    void boolean(const Json& object, const char* key, const std::string& where) const {
        const Json* value = member(object, key);
        if (value && !value->is_boolean()) fail(where + "." + key, "expected true or false, got " + value->dump());
    }

    // An optional string, one of `choices` when given.
    void one_of(const Json& object, const char* key, const std::string& where,
                std::initializer_list<const char*> choices) const {
        const Json* value = member(object, key);
        if (!value) return;
        std::string listed;
        for (const char* choice : choices) {
            if (value->is_string() && value->get_ref<const std::string&>() == choice) return;
            listed += (listed.empty() ? "" : ", ") + std::string(choice);
        }
        fail(where + "." + key, "expected one of " + listed + ", got " + value->dump());
    }

    // An optional integer, one of `choices` (the sampler's GL enums).
    void enumerant(const Json& object, const char* key, const std::string& where,
                   std::initializer_list<int64_t> choices) const {
        const Json* value = member(object, key);
        if (!value) return;
        std::string listed;
        for (const int64_t choice : choices) {
            if (value->is_number_integer() && value->get<int64_t>() == choice) return;
            listed += (listed.empty() ? "" : ", ") + std::to_string(choice);
        }
        fail(where + "." + key, "expected one of " + listed + ", got " + value->dump());
    }

    // Calls check(element, "name[i]") for every element of `array` (when it is an array;
    // the structural checks name a non-array).
    template <typename Check>
    void each(const Json* array, const std::string& name, Check&& check) const {
        if (!array || !array->is_array()) return;
        for (size_t i = 0; i < array->size(); ++i) check((*array)[i], name + "[" + std::to_string(i) + "]");
    }

private:
    void number_value(const Json& value, const std::string& where, const Range& range) const {
        if (!value.is_number()) fail(where, "expected " + range.text() + ", got " + value.dump());
        const double number = value.get<double>();
        if (!std::isfinite(number) || !range.holds(number)) {
            fail(where, "expected " + range.text() + ", got " + value.dump());
        }
    }

    const std::string& origin_;
};

// glTF 2.0 names its major version 2; a 1.0 file has another schema altogether.
void check_asset(const ValueChecker& checker, const Json& document) {
    const Json* asset = ValueChecker::member(document, "asset");
    if (!asset) checker.fail("asset", "missing (every glTF file has an asset with its version)");
    const Json* version = ValueChecker::member(*asset, "version");
    if (!version || !version->is_string()) {
        checker.fail("asset.version", "expected a version string such as \"2.0\", got " +
                                          (version ? version->dump() : std::string("nothing")));
    }
    const std::string& text = version->get_ref<const std::string&>();
    if (text.size() < 3 || text.compare(0, 2, "2.") != 0) {
        checker.fail("asset.version", "Penumbra reads glTF 2.x files, this one is version \"" + text + "\"");
    }
}

// A node's transform: TRS properties or a matrix, each of the right length and kind (the
// rotation a quaternion, its components within [-1, 1]).
void check_node(const ValueChecker& checker, const Json& node, const std::string& where) {
    checker.numbers(node, "translation", where, 3, kAnyNumber);
    checker.numbers(node, "rotation", where, 4, kSigned);
    checker.numbers(node, "scale", where, 3, kAnyNumber);
    checker.numbers(node, "matrix", where, 16, kAnyNumber);
    checker.numbers(node, "weights", where, ValueChecker::kAnyLength, kAnyNumber);
}

// KHR_texture_transform on a textureInfo: an offset, a rotation, a scale.
void check_texture_info(const ValueChecker& checker, const Json& owner, const char* key, const std::string& where) {
    const Json* info = ValueChecker::member(owner, key);
    if (!info) return;
    const std::string at = where + "." + key;
    checker.number(*info, "scale", at, kAnyNumber);  // normalTexture
    checker.number(*info, "strength", at, kUnit);    // occlusionTexture
    const Json* extensions = ValueChecker::member(*info, "extensions");
    const Json* transform = extensions ? ValueChecker::member(*extensions, "KHR_texture_transform") : nullptr;
    if (!transform) return;
    const std::string transform_at = at + ".extensions.KHR_texture_transform";
    checker.numbers(*transform, "offset", transform_at, 2, kAnyNumber);
    checker.number(*transform, "rotation", transform_at, kAnyNumber);
    checker.numbers(*transform, "scale", transform_at, 2, kAnyNumber);
}

void check_material(const ValueChecker& checker, const Json& material, const std::string& where) {
    if (const Json* pbr = ValueChecker::member(material, "pbrMetallicRoughness")) {
        const std::string at = where + ".pbrMetallicRoughness";
        checker.numbers(*pbr, "baseColorFactor", at, 4, kUnit);
        checker.number(*pbr, "metallicFactor", at, kUnit);
        checker.number(*pbr, "roughnessFactor", at, kUnit);
        check_texture_info(checker, *pbr, "baseColorTexture", at);
        check_texture_info(checker, *pbr, "metallicRoughnessTexture", at);
    }
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) {
        check_texture_info(checker, material, key, where);
    }
    checker.numbers(material, "emissiveFactor", where, 3, kUnit);
    checker.one_of(material, "alphaMode", where, {"OPAQUE", "MASK", "BLEND"});
    checker.number(material, "alphaCutoff", where, kNonNegative);
    checker.boolean(material, "doubleSided", where);
    const Json* extensions = ValueChecker::member(material, "extensions");
    if (const Json* strength =
            extensions ? ValueChecker::member(*extensions, "KHR_materials_emissive_strength") : nullptr) {
        checker.number(*strength, "emissiveStrength", where + ".extensions.KHR_materials_emissive_strength",
                       kNonNegative);
    }
    if (const Json* gloss =
            extensions ? ValueChecker::member(*extensions, "KHR_materials_pbrSpecularGlossiness") : nullptr) {
        const std::string at = where + ".extensions.KHR_materials_pbrSpecularGlossiness";
        checker.numbers(*gloss, "diffuseFactor", at, 4, kUnit);
        check_texture_info(checker, *gloss, "diffuseTexture", at);
    }
}

// KHR_lights_punctual: a type, a linear colour in [0, 1], a non-negative intensity, a
// positive range, and a spot's cone with 0 <= inner < outer <= pi / 2.
void check_light(const ValueChecker& checker, const Json& light, const std::string& where) {
    if (!ValueChecker::member(light, "type")) checker.fail(where + ".type", "missing (directional, point or spot)");
    checker.one_of(light, "type", where, {"directional", "point", "spot"});
    checker.numbers(light, "color", where, 3, kUnit);
    checker.number(light, "intensity", where, kNonNegative);
    checker.number(light, "range", where, kPositive);
    const Json* spot = ValueChecker::member(light, "spot");
    if (!spot) return;
    const std::string at = where + ".spot";
    checker.number(*spot, "innerConeAngle", at, {0.0, kHalfPi, false, true});
    checker.number(*spot, "outerConeAngle", at, {0.0, kHalfPi, true, false});
    const Json* inner = ValueChecker::member(*spot, "innerConeAngle");
    const Json* outer = ValueChecker::member(*spot, "outerConeAngle");
    const double inner_angle = inner ? inner->get<double>() : 0.0;
    const double outer_angle = outer ? outer->get<double>() : kHalfPi / 2.0;  // the extension's default
    if (inner_angle >= outer_angle) {
        checker.fail(at + ".innerConeAngle", "expected less than outerConeAngle (" + Json(outer_angle).dump() +
                                                 "), got " + Json(inner_angle).dump());
    }
}

void check_sampler(const ValueChecker& checker, const Json& sampler, const std::string& where) {
    checker.enumerant(sampler, "magFilter", where, {9728, 9729});
    checker.enumerant(sampler, "minFilter", where, {9728, 9729, 9984, 9985, 9986, 9987});
    checker.enumerant(sampler, "wrapS", where, {33071, 33648, 10497});
    checker.enumerant(sampler, "wrapT", where, {33071, 33648, 10497});
}

void check_accessor(const ValueChecker& checker, const Json& accessor, const std::string& where) {
    checker.one_of(accessor, "type", where, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"});
    checker.boolean(accessor, "normalized", where);
    for (const char* bound : {"min", "max"})
        checker.numbers(accessor, bound, where, ValueChecker::kAnyLength, kAnyNumber);
}

// A camera Penumbra may take the view from: a perspective one's positive field of view
// and near plane, a far plane beyond it; an orthographic one's extents.
void check_camera(const ValueChecker& checker, const Json& camera, const std::string& where) {
    checker.one_of(camera, "type", where, {"perspective", "orthographic"});
    if (const Json* perspective = ValueChecker::member(camera, "perspective")) {
        const std::string at = where + ".perspective";
        checker.number(*perspective, "yfov", at, kPositive);
        checker.number(*perspective, "znear", at, kPositive);
        checker.number(*perspective, "zfar", at, kPositive);
        checker.number(*perspective, "aspectRatio", at, kPositive);
    }
    if (const Json* orthographic = ValueChecker::member(camera, "orthographic")) {
        const std::string at = where + ".orthographic";
        checker.number(*orthographic, "xmag", at, kAnyNumber);
        checker.number(*orthographic, "ymag", at, kAnyNumber);
        checker.number(*orthographic, "znear", at, kNonNegative);
        checker.number(*orthographic, "zfar", at, kPositive);
    }
}

}  // namespace

void check_gltf_json_values(const nlohmann::json& document, const std::string& origin) {
    const ValueChecker checker(origin);
    check_asset(checker, document);
    checker.each(ValueChecker::member(document, "nodes"), "nodes",
                 [&](const Json& node, const std::string& where) { check_node(checker, node, where); });
    checker.each(ValueChecker::member(document, "materials"), "materials",
                 [&](const Json& material, const std::string& where) { check_material(checker, material, where); });
    checker.each(ValueChecker::member(document, "samplers"), "samplers",
                 [&](const Json& sampler, const std::string& where) { check_sampler(checker, sampler, where); });
    checker.each(ValueChecker::member(document, "accessors"), "accessors",
                 [&](const Json& accessor, const std::string& where) { check_accessor(checker, accessor, where); });
    checker.each(ValueChecker::member(document, "cameras"), "cameras",
                 [&](const Json& camera, const std::string& where) { check_camera(checker, camera, where); });
    const Json* extensions = ValueChecker::member(document, "extensions");
    const Json* punctual = extensions ? ValueChecker::member(*extensions, "KHR_lights_punctual") : nullptr;
    checker.each(punctual ? ValueChecker::member(*punctual, "lights") : nullptr,
                 "extensions.KHR_lights_punctual.lights",
                 [&](const Json& light, const std::string& where) { check_light(checker, light, where); });
}

}  // namespace penumbra
