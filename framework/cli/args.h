// voxlab CLI: a small option parser. Options are declared up front (so the
// parser knows which take a value), accept "--name VALUE" and "--name=VALUE",
// and anything undeclared is an error naming it.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace voxlab::cli {

struct OptionSpec {
    std::string name;     // without the dashes
    std::string value;    // e.g. "WxH"; empty for a flag
    std::string help;
};

class Args {
public:
    // Parses argv[first..]; throws voxlab::Error on an unknown option or a
    // missing value.
    Args(const std::vector<OptionSpec>& specs, int argc, char** argv, int first,
         const std::string& command);

    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::optional<std::string> get(const std::string& name) const;
    std::vector<std::string> getAll(const std::string& name) const;
    const std::vector<std::string>& positionals() const { return positionals_; }

private:
    std::multimap<std::string, std::string> values_;
    std::vector<std::string> positionals_;
};

// "  --size WxH      image size in pixels" lines for --help.
std::string formatOptions(const std::vector<OptionSpec>& specs);

// What a command does when asked for --help, or called wrongly (`wrong`):
// prints `usage` and the options, and gives the exit status (0 for --help,
// 2 otherwise); std::nullopt when the command should run.
std::optional<int> usageExit(const Args& args, bool wrong, const std::string& usage,
                             const std::vector<OptionSpec>& specs);

// Strict number parsing for option values; errors name the option.
double parseNumber(const std::string& text, const std::string& option);
int parseInt(const std::string& text, const std::string& option);
std::vector<double> parseNumberList(const std::string& text, const std::string& option, std::size_t count);

}  // namespace voxlab::cli
