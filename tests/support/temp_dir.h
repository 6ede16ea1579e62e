// Test support: a fresh temporary folder, and whole files read and written.
#pragma once

#include <stdlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace voxlab::testing {

// A file's bytes as a string ("" when it cannot be read, a folder included:
// the stream operator catches the read error an iterator would throw).
inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    if (in) text << in.rdbuf();
    return text.str();
}

// A new folder under the system's temporary folder, named PREFIX-XXXXXX,
// removed with everything in it when the object goes.
class TempDir {
public:
    explicit TempDir(const std::string& prefix = "voxlab-test") {
        std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed for " + pattern);
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

    // Writes `text`, then `data`, to NAME in the folder (its folders made);
    // returns the file's path.
    std::string write(const std::string& name, const std::string& text,
                      const std::vector<std::uint8_t>& data = {}) const {
        const std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream out(p, std::ios::binary);
        out.write(text.data(), std::streamsize(text.size()));
        out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
        return p.string();
    }

private:
    std::filesystem::path path_;
};

}  // namespace voxlab::testing
