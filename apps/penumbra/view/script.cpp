#include "script.hpp"

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "penumbra/errors.hpp"
#include "penumbra/scene/settings_files.hpp"

namespace penumbra::view {
namespace {

// One line's words after FRAME and VERB, with the "FILE:LINE" used in errors.
struct Line {
    std::vector<std::string> args;
    std::string rest;  // the text after the verb, for `set`
    std::string origin;

    [[noreturn]] void fail(const std::string& problem) const { throw InputError(origin + ": " + problem); }

    void expect_count(size_t count, const std::string& usage) const {
        if (args.size() != count) fail("expected " + usage);
    }

    float number(size_t index) const {
        try {
            size_t used = 0;
            const float value = std::stof(args[index], &used);
            if (used == args[index].size() && std::isfinite(value)) return value;
        } catch (const std::exception&) {
        }
        fail("\"" + args[index] + "\" is not a number");
    }

    uint32_t size(size_t index) const {
        const float value = number(index);
        if (value < 1.0f || value > 16384.0f || value != static_cast<float>(static_cast<uint32_t>(value))) {
            fail("\"" + args[index] + "\" is not a size in pixels (1..16384)");
        }
        return static_cast<uint32_t>(value);
    }
};

using Parser = std::function<Action(const Line&)>;

Action parse_set(const Line& line) {
    // "set TABLE.KEY = VALUE" is the config-file line "KEY = VALUE" under [TABLE].
    const size_t dot = line.rest.find('.');
    const size_t equals = line.rest.find('=');
    if (dot == std::string::npos || equals == std::string::npos || dot > equals) {
        line.fail("expected set TABLE.KEY = VALUE (e.g. set shadow.cascades = 2)");
    }
    std::string table = line.rest.substr(0, dot);
    table.erase(0, table.find_first_not_of(" \t"));
    const std::string assignment = line.rest.substr(dot + 1);
    return action::Set{parse_settings_text("[" + table + "]\n" + assignment + "\n", line.origin), line.origin};
}

const std::map<std::string, Parser>& parsers() {
    static const std::map<std::string, Parser> table{
        {"set", parse_set},
        {"move",
         [](const Line& l) -> Action {
             l.expect_count(3, "move RIGHT UP FORWARD (metres)");
             return action::Move{{l.number(0), l.number(1), l.number(2)}};
         }},
        {"turn",
         [](const Line& l) -> Action {
             l.expect_count(2, "turn YAW PITCH (degrees)");
             return action::Turn{l.number(0), l.number(1)};
         }},
        {"mode",
         [](const Line& l) -> Action {
             l.expect_count(1, "mode fly|orbit");
             if (l.args[0] == "fly") return action::Mode{CameraMode::Fly};
             if (l.args[0] == "orbit") return action::Mode{CameraMode::Orbit};
             l.fail("unknown camera mode \"" + l.args[0] + "\" (expected fly, orbit)");
         }},
        {"zoom",
         [](const Line& l) -> Action {
             l.expect_count(1, "zoom FACTOR");
             const float factor = l.number(0);
             if (!(factor > 0.0f)) l.fail("zoom factor must be > 0");
             return action::Zoom{factor};
         }},
        {"sun",
         [](const Line& l) -> Action {
             l.expect_count(2, "sun AZIMUTH ELEVATION (degrees)");
             return action::Sun{{l.number(0), l.number(1)}};
         }},
        {"animate-sun",
         [](const Line& l) -> Action {
             l.expect_count(1, "animate-sun DEGREES_PER_SECOND");
             return action::AnimateSun{l.number(0)};
         }},
        {"resize",
         [](const Line& l) -> Action {
             l.expect_count(2, "resize WIDTH HEIGHT");
             return action::Resize{l.size(0), l.size(1)};
         }},
        {"reset-camera",
         [](const Line& l) -> Action {
             l.expect_count(0, "reset-camera (no arguments)");
             return action::ResetCamera{};
         }},
        {"ui",
         [](const Line& l) -> Action {
             l.expect_count(1, "ui show|hide");
             if (l.args[0] != "show" && l.args[0] != "hide") l.fail("expected ui show|hide");
             return action::Ui{l.args[0] == "show"};
         }},
        {"screenshot",
         [](const Line& l) -> Action {
             l.expect_count(1, "screenshot FILE");
             return action::Screenshot{l.args[0]};
         }},
        {"save-settings",
         [](const Line& l) -> Action {
             l.expect_count(1, "save-settings FILE");
             return action::SaveSettings{l.args[0]};
         }},
        {"quit",
         [](const Line& l) -> Action {
             l.expect_count(0, "quit (no arguments)");
             return action::Quit{};
         }},
    };
    return table;
}

std::string strip_comment(const std::string& text) {
    const size_t hash = text.find('#');
    return hash == std::string::npos ? text : text.substr(0, hash);
}

}  // namespace

std::vector<TimedAction> parse_script(const std::string& text, const std::string& origin) {
    std::vector<TimedAction> actions;
    std::istringstream lines(text);
    std::string raw;
    for (int number = 1; std::getline(lines, raw); ++number) {
        std::istringstream words(strip_comment(raw));
        std::string frame_text, verb;
        if (!(words >> frame_text)) continue;  // blank or comment
        Line line;
        line.origin = origin + ":" + std::to_string(number);
        uint32_t frame = 0;
        try {
            size_t used = 0;
            const unsigned long value = std::stoul(frame_text, &used);
            if (used != frame_text.size() || frame_text[0] == '-') throw std::invalid_argument(frame_text);
            frame = static_cast<uint32_t>(value);
        } catch (const std::exception&) {
            line.fail("expected a frame number first, got \"" + frame_text + "\"");
        }
        if (!actions.empty() && frame < actions.back().frame) line.fail("frames must not decrease");
        if (!(words >> verb)) line.fail("expected an action after the frame number");
        std::getline(words, line.rest);
        std::istringstream arguments(line.rest);
        for (std::string word; arguments >> word;) line.args.push_back(word);
        const auto parser = parsers().find(verb);
        if (parser == parsers().end()) line.fail("unknown action \"" + verb + "\"");
        actions.push_back({frame, parser->second(line), line.origin});
    }
    return actions;
}

std::vector<TimedAction> load_script(const std::filesystem::path& path) {
    std::ifstream file(path);
    if (!file) throw InputError(path.string() + ": script file not found");
    std::stringstream text;
    text << file.rdbuf();
    return parse_script(text.str(), path.string());
}

}  // namespace penumbra::view
