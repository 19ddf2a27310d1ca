// Every penumbra::Error is one printable line, whatever text it carries (issue 17): control
// characters from a file or a caller are escaped, everything else is kept as it is.
#include <gtest/gtest.h>

#include <string>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

TEST(ErrorMessages, ControlCharactersAreEscaped) {
    const std::string text = std::string("a\nb\tc\r\x01\x1f\x7f") + '\0' + "d";
    EXPECT_EQ(std::string(InputError(text).what()), "a\\nb\\tc\\r\\x01\\x1f\\x7f\\x00d");
    EXPECT_EQ(std::string(VulkanError(text, VK_ERROR_UNKNOWN).what()), "a\\nb\\tc\\r\\x01\\x1f\\x7f\\x00d");
}

TEST(ErrorMessages, PrintableTextIsUnchanged) {
    const std::string text = "scene.toml: objects[0].size: \"1e39\" is not finite (UTF-8: \xc3\xa9, \\n stays)";
    EXPECT_EQ(std::string(UsageError(text).what()), text);
}

}  // namespace
}  // namespace penumbra
