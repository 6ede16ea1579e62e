// The expected outputs' cache (see expected_cache.h).
//
// The key is FNV-1a with 128 bits (offset basis and prime from the published
// FNV parameters, http://www.isthe.com/chongo/tech/comp/fnv/) over the worker
// program's bytes, then each input tree's files in sorted order
// of their relative path, each as its path, its size and its bytes. It is not
// a defence against someone who can write the inputs (they could change the
// reference itself); it tells one set of inputs from another.
#include "voxlab/expected_cache.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "voxlab/project_root.h"
#include "voxlab/scene.h"

namespace voxlab::expected_cache {

namespace fs = std::filesystem;

namespace {

constexpr int kKeptKeys = 8;

class Fnv128 {
public:
    void add(const char* bytes, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            h_ ^= static_cast<unsigned char>(bytes[i]);
            h_ *= kPrime;
        }
    }
    void add(const std::string& s) { add(s.data(), s.size() + 1); }  // with its terminating zero
    std::string hex() const {
        char buf[33];
        std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(h_ >> 64),
                      static_cast<unsigned long long>(h_));
        return buf;
    }

private:
    using u128 = unsigned __int128;
    static constexpr u128 kPrime = (u128(1) << 88) | 0x13b;
    u128 h_ = (u128(0x6c62272e07bb0142ULL) << 64) | 0x62b821756295c58dULL;
};

void addFile(Fnv128& hash, const fs::path& file, const std::string& name) {
    hash.add(name);
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        hash.add("(unreadable)");
        return;
    }
    std::vector<char> buffer(1 << 20);
    std::size_t size = 0;
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        const std::size_t got = std::size_t(in.gcount());
        hash.add(buffer.data(), got);
        size += got;
    }
    hash.add(std::to_string(size));
}

// Every regular file under `root` (links followed: datasets may be links to
// shared copies), in sorted order of their path relative to it.
void addTree(Fnv128& hash, const fs::path& root) {
    hash.add(root.filename().string());
    std::error_code ec;
    if (!fs::is_directory(root, ec)) {
        hash.add("(absent)");
        return;
    }
    std::vector<std::pair<std::string, fs::path>> files;
    for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec)) files.emplace_back(fs::relative(it->path(), root).string(), it->path());
    std::sort(files.begin(), files.end());
    for (const auto& [name, path] : files) addFile(hash, path, name);
}

fs::path entryFolder(const std::string& key) { return fs::path(*folder()) / key; }

// Marks `key` used now, and removes all but the kKeptKeys most recently used.
void touchAndPrune(const std::string& key) {
    std::error_code ec;
    fs::last_write_time(entryFolder(key), fs::file_time_type::clock::now(), ec);
    std::vector<std::pair<fs::file_time_type, fs::path>> keys;
    for (const auto& entry : fs::directory_iterator(*folder(), ec))
        if (entry.is_directory(ec) && entry.path().filename().string().size() == 32)
            keys.emplace_back(entry.last_write_time(ec), entry.path());
    std::sort(keys.rbegin(), keys.rend());
    for (std::size_t i = kKeptKeys; i < keys.size(); ++i) fs::remove_all(keys[i].second, ec);
}

}  // namespace

std::optional<std::string> folder() {
    if (const char* env = std::getenv("VOXLAB_EXPECTED_CACHE")) {
        const std::string value = env;
        if (value.empty() || value == "off") return std::nullopt;
        return fs::absolute(value).lexically_normal().string();
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "voxlab" / "expected").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".cache" / "voxlab" / "expected").string();
    return std::nullopt;
}

std::string key(const std::string& worker, const std::string& referenceRoot) {
    Fnv128 hash;
    addFile(hash, worker.empty() ? fs::path("/proc/self/exe") : fs::path(worker), "worker");
    const fs::path project = projectRoot();
    for (const fs::path& tree : {project / "shaders", fs::path(stagesRoot()), project / "datasets", fs::path(referenceRoot),
                                 project / "framework" / "include", project / "framework" / "stage_library"})
        addTree(hash, tree);
    return hash.hex();
}

bool restore(const std::string& key, const std::string& name, const std::string& destination) {
    if (!folder()) return false;
    const fs::path from = entryFolder(key) / name;
    std::error_code ec;
    if (!fs::exists(from, ec)) return false;
    fs::remove_all(destination, ec);
    fs::create_directories(fs::path(destination).parent_path(), ec);
    fs::copy(from, destination, fs::copy_options::recursive, ec);
    if (ec) {
        fs::remove_all(destination, ec);
        return false;
    }
    touchAndPrune(key);
    return true;
}

void store(const std::string& key, const std::string& name, const std::string& source) {
    if (!folder()) return;
    std::error_code ec;
    const fs::path entry = entryFolder(key) / name;
    if (fs::exists(entry, ec)) return;
    fs::create_directories(entryFolder(key), ec);
    const fs::path temporary = entryFolder(key) / (".incoming_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(temporary, ec);
    fs::copy(source, temporary, fs::copy_options::recursive, ec);
    if (!ec) fs::rename(temporary, entry, ec);  // another run may have stored it first: keep theirs
    fs::remove_all(temporary, ec);
    touchAndPrune(key);
}

}  // namespace voxlab::expected_cache
