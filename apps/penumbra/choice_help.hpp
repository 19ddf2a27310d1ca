#pragma once
// Help text for a flag that takes a choice, from the choice's table in penumbra/settings.hpp,
// so that a new value shows in --help without another list to edit.
#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>

#include "penumbra/settings.hpp"

namespace penumbra::cli {

// "a|b|c", with " (default)" after `marked_default`'s name when given.
template <typename Enum, std::size_t N>
std::string choice_list(const ChoiceName<Enum> (&choices)[N],
                        std::optional<std::type_identity_t<Enum>> marked_default = {}) {
    std::string list;
    for (const ChoiceName<Enum>& choice : choices) {
        list += (list.empty() ? "" : "|") + std::string(choice.name);
        if (marked_default && choice.value == *marked_default) list += " (default)";
    }
    return list;
}

}  // namespace penumbra::cli
