// voxlab CLI: option parsing (see args.h).
#include "args.h"

#include <iostream>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "voxlab/error.h"

namespace voxlab::cli {

Args::Args(const std::vector<OptionSpec>& specs, int argc, char** argv, int first,
           const std::string& command) {
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) {
            positionals_.push_back(arg);
            continue;
        }
        std::string name = arg.substr(2), value;
        const std::size_t eq = name.find('=');
        const bool inlineValue = eq != std::string::npos;
        if (inlineValue) value = name.substr(eq + 1), name = name.substr(0, eq);
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& s : specs)
            if (s.name == name) spec = &s;
        if (!spec) throw Error(command + ": unknown option --" + name + " (see voxlab " + command + " --help)");
        if (!spec->value.empty() && !inlineValue) {
            if (i + 1 >= argc) throw Error(command + ": option --" + name + " needs a value (" + spec->value + ")");
            value = argv[++i];
        } else if (spec->value.empty() && inlineValue) {
            throw Error(command + ": option --" + name + " takes no value");
        }
        values_.emplace(name, value);
    }
}

std::optional<std::string> Args::get(const std::string& name) const {
    auto range = values_.equal_range(name);
    if (range.first == range.second) return std::nullopt;
    return std::prev(range.second)->second;  // the last one given wins
}

std::vector<std::string> Args::getAll(const std::string& name) const {
    std::vector<std::string> out;
    auto range = values_.equal_range(name);
    for (auto it = range.first; it != range.second; ++it) out.push_back(it->second);
    return out;
}

std::optional<int> usageExit(const Args& args, bool wrong, const std::string& usage,
                             const std::vector<OptionSpec>& specs) {
    if (!args.has("help") && !wrong) return std::nullopt;
    std::cout << usage << formatOptions(specs);
    return args.has("help") ? 0 : 2;
}

std::string formatOptions(const std::vector<OptionSpec>& specs) {
    std::ostringstream out;
    for (const OptionSpec& s : specs) {
        std::string left = "  --" + s.name + (s.value.empty() ? "" : " " + s.value);
        if (left.size() < 30) left.resize(30, ' ');
        else left += "\n" + std::string(30, ' ');
        out << left << s.help << "\n";
    }
    return out.str();
}

double parseNumber(const std::string& text, const std::string& option) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
        throw Error("option " + option + ": '" + text + "' is not a number");
    return v;
}

int parseInt(const std::string& text, const std::string& option) {
    const double v = parseNumber(text, option);
    if (v != std::floor(v) || std::abs(v) > 1e9) throw Error("option " + option + ": '" + text + "' is not an integer");
    return int(v);
}

std::vector<double> parseNumberList(const std::string& text, const std::string& option, std::size_t count) {
    std::vector<double> out;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ',')) out.push_back(parseNumber(item, option));
    if (out.size() != count)
        throw Error("option " + option + ": expected " + std::to_string(count) + " comma-separated numbers, got '" +
                    text + "'");
    return out;
}

}  // namespace voxlab::cli
