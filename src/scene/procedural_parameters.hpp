#pragma once
// The query of a procedural built-in scene ("builtin:forest?count=1000&spots=8"): "KEY=N"
// pairs joined by '&', each key at most once, each value an integer in its range.
#include <set>
#include <span>
#include <sstream>
#include <string>

#include "penumbra/errors.hpp"

namespace penumbra {

template <typename Parameters>
struct ProceduralParameter {
    const char* key;
    uint32_t min;
    uint32_t max;
    uint32_t Parameters::*field;
};

namespace procedural_detail {

// "count=N, spots=N or movers=N", as error messages name the keys.
template <typename Parameters>
std::string key_list(std::span<const ProceduralParameter<Parameters>> specs) {
    std::string list;
    for (size_t i = 0; i < specs.size(); ++i) {
        list += (i == 0 ? "" : i + 1 == specs.size() ? " or " : ", ") + std::string(specs[i].key) + "=N";
    }
    return list;
}

template <typename Parameters>
uint32_t parse_value(const ProceduralParameter<Parameters>& spec, const std::string& digits,
                     const std::string& origin) {
    const bool numeric =
        !digits.empty() && digits.size() <= 9 && digits.find_first_not_of("0123456789") == std::string::npos;
    const unsigned long value = numeric ? std::stoul(digits) : 0;
    if (!numeric || value < spec.min || value > spec.max) {
        throw InputError(origin + ": " + spec.key + ": expected an integer from " + std::to_string(spec.min) + " to " +
                         std::to_string(spec.max) + ", got \"" + digits + "\"");
    }
    return static_cast<uint32_t>(value);
}

}  // namespace procedural_detail

// `defaults` with the query's values. Throws InputError naming `origin`, the key and the value.
template <typename Parameters>
Parameters parse_procedural_parameters(const std::string& query, const std::string& origin,
                                       std::span<const ProceduralParameter<Parameters>> specs, Parameters defaults) {
    Parameters parameters = defaults;
    if (query.empty()) return parameters;
    const std::string keys = procedural_detail::key_list(specs);
    std::set<std::string> seen;
    std::istringstream items(query);
    for (std::string item; std::getline(items, item, '&');) {
        const size_t equals = item.find('=');
        const ProceduralParameter<Parameters>* spec = nullptr;
        for (const ProceduralParameter<Parameters>& candidate : specs) {
            if (item.substr(0, equals) == candidate.key) spec = &candidate;
        }
        if (equals == std::string::npos || !spec) {
            throw InputError(origin + ": expected " + keys + " joined by '&', got \"" + item + "\"");
        }
        if (!seen.insert(spec->key).second) throw InputError(origin + ": " + spec->key + ": given twice");
        parameters.*(spec->field) = procedural_detail::parse_value(*spec, item.substr(equals + 1), origin);
    }
    if (query.back() == '&') throw InputError(origin + ": expected " + keys + " after the last '&'");
    return parameters;
}

}  // namespace penumbra
