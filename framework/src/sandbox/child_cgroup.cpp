// voxlab: the cgroup that holds a sandboxed child and everything it starts
// (ChildCgroup, child_process.h).
//
// Linux offers two layouts. cgroup v2 has one tree in which a folder's
// files (pids.max, memory.max) exist once its parent's subtree_control
// enables the controller. cgroup v1 (still the default of many container
// hosts, and of this project's CI machine) has one tree per controller,
// mounted separately (/sys/fs/cgroup/memory, /sys/fs/cgroup/pids), with
// memory.limit_in_bytes and memory.memsw.limit_in_bytes. Each controller is
// taken from v1 where a v1 tree holds it, else from v2. Where this process's
// own folder is found is read from /proc/self/cgroup and, for where each tree
// is mounted and which part of it a container sees, /proc/self/mountinfo.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "voxlab/child_process.h"

namespace voxlab {

namespace {

namespace fs = std::filesystem;

struct Mount {
    std::string point, root;
};

std::vector<std::string> splitOn(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator)) parts.push_back(part);
    return parts;
}

bool listHas(const std::string& commaList, const std::string& item) {
    for (const std::string& s : splitOn(commaList, ','))
        if (s == item) return true;
    return false;
}

// The mount of the v1 tree that holds `controller`, or of the v2 tree
// (controller empty).
std::optional<Mount> cgroupMount(const std::string& controller) {
    std::ifstream in("/proc/self/mountinfo");
    for (std::string line; std::getline(in, line);) {
        const std::vector<std::string> f = splitOn(line, ' ');
        std::size_t dash = 0;
        while (dash < f.size() && f[dash] != "-") ++dash;
        if (dash < 5 || dash + 3 >= f.size()) continue;
        const std::string& type = f[dash + 1];
        const bool match = controller.empty() ? type == "cgroup2"
                                              : type == "cgroup" && listHas(f[dash + 3], controller);
        if (match) return Mount{f[4], f[3]};
    }
    return std::nullopt;
}

// This process's folder in the tree that holds `controller` (empty: v2).
std::optional<fs::path> ownFolder(const std::string& controller) {
    const std::optional<Mount> mount = cgroupMount(controller);
    if (!mount) return std::nullopt;
    std::ifstream in("/proc/self/cgroup");
    for (std::string line; std::getline(in, line);) {
        const std::size_t a = line.find(':'), b = line.find(':', a + 1);
        if (a == std::string::npos || b == std::string::npos) continue;
        const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
        if (controller.empty() ? !controllers.empty() || line.compare(0, a, "0") != 0
                               : !listHas(controllers, controller))
            continue;
        // The mount shows the tree from mount->root down (a container's view).
        const std::string root = mount->root == "/" ? "" : mount->root;
        if (path.compare(0, root.size(), root) != 0) return std::nullopt;
        return fs::path(mount->point) / path.substr(root.size()).substr(path.size() > root.size() ? 1 : 0);
    }
    return std::nullopt;
}

bool writeText(const fs::path& file, const std::string& text) {
    std::ofstream out(file);
    return out << text && out.flush();
}

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string uniqueName() {
    static std::atomic<int> counter{0};
    return "voxlab-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
}

bool listsWord(const std::string& text, const std::string& word) {
    std::istringstream in(text);
    for (std::string w; in >> w;)
        if (w == word) return true;
    return false;
}

// v2: a controller is usable in a child folder once the parent's
// subtree_control lists it. Asks for it. Where this process's own folder
// holds processes and is not the tree's root (a container's own cgroup, as
// a GPU machine's or Gradescope's), the kernel refuses ("no internal
// processes"): then the folder's processes, this one among them, move into
// a leaf folder of it, voxlab-leaf, and the request is made again. A
// process that cannot move (a kernel thread) leaves the controller off.
bool v2Enabled(const fs::path& parent, const std::string& controller) {
    const fs::path control = parent / "cgroup.subtree_control";
    for (int attempt = 0; attempt < 4; ++attempt) {
        if (listsWord(readText(control), controller)) return true;
        if (writeText(control, "+" + controller)) continue;
        // Refused: empty this folder of processes into the leaf, then ask again.
        const fs::path leaf = parent / "voxlab-leaf";
        std::error_code ec;
        fs::create_directory(leaf, ec);
        if (ec) return false;
        std::ifstream procs(parent / "cgroup.procs");
        for (long pid; procs >> pid;) writeText(leaf / "cgroup.procs", std::to_string(pid) + "\n");
    }
    return listsWord(readText(control), controller);
}

// The folder `name` for `controller` (made, or there already: v2 holds both
// controllers in one), from its v1 tree, else from v2; empty when none.
std::string folderFor(const std::string& controller, const std::string& name, bool* v2) {
    std::optional<fs::path> own = ownFolder(controller);
    *v2 = !own;
    if (!own) {
        own = ownFolder("");
        // Moved into the leaf by an earlier call: the stages go beside it.
        if (own && own->filename() == "voxlab-leaf") own = own->parent_path();
        if (!own || !v2Enabled(*own, controller)) return "";
    }
    std::error_code ec;
    if (!fs::exists(*own / "cgroup.procs", ec)) return "";
    fs::create_directory(*own / name, ec);
    return !ec && fs::is_directory(*own / name, ec) ? (*own / name).string() : "";
}

}  // namespace

ChildCgroup::ChildCgroup(int maxProcesses, std::size_t memoryBytes) {
    const std::string name = uniqueName();
    // Writes the limits into the folder for `controller`, or removes it.
    auto limited = [&](const std::string& controller, const std::vector<std::pair<std::string, std::string>>& files) {
        bool v2 = false;
        const std::string dir = folderFor(controller, name, &v2);
        if (dir.empty()) return std::string();
        // The first file must take its value; the others exist only where
        // the kernel has them.
        bool ok = true;
        for (std::size_t i = 0; i < files.size(); ++i)
            if (i == 0 || fs::exists(fs::path(dir) / files[i].first))
                ok = ok && writeText(fs::path(dir) / files[i].first, files[i].second + "\n");
        const bool shared = std::find(dirs_.begin(), dirs_.end(), dir) != dirs_.end();
        if (!ok) {
            if (!shared) rmdir(dir.c_str());
            return std::string();
        }
        if (!shared) {
            dirs_.push_back(dir);
            procs_.push_back(dir + "/cgroup.procs");
        }
        if (controller == "memory") v2_ = v2;
        return dir;
    };
    if (maxProcesses > 0) pidsDir_ = limited("pids", {{"pids.max", std::to_string(maxProcesses)}});
    if (memoryBytes > 0) {
        const std::string bytes = std::to_string(memoryBytes);
        // The first file must take the cap; swap is counted too where the
        // kernel accounts it (v1: memory and swap together; v2: no swap).
        memoryDir_ = ownFolder("memory")
                         ? limited("memory", {{"memory.limit_in_bytes", bytes}, {"memory.memsw.limit_in_bytes", bytes}})
                         : limited("memory", {{"memory.max", bytes}, {"memory.swap.max", "0"}});
    }
}

void ChildCgroup::killAll() const {
    // Forks in between are caught by the repeats.
    for (int round = 0; round < 50; ++round) {
        bool any = false;
        for (const std::string& procs : procs_) {
            std::ifstream in(procs);
            for (long pid; in >> pid;)
                if (pid > 0) any = true, kill(pid_t(pid), SIGKILL);
        }
        if (!any) return;
        usleep(10000);
    }
}

long ChildCgroup::oomKills() const {
    if (memoryDir_.empty()) return 0;
    // v2: memory.events; v1 (Linux 4.13+): memory.oom_control.
    const std::string text = readText(fs::path(memoryDir_) / (v2_ ? "memory.events" : "memory.oom_control"));
    const std::size_t at = text.find("oom_kill ");
    return at == std::string::npos ? 0 : std::atol(text.c_str() + at + 9);
}

ChildCgroup::~ChildCgroup() {
    if (dirs_.empty()) return;
    killAll();
    // The namespace's processes may take a moment to leave after a kill.
    for (const std::string& dir : dirs_)
        for (int i = 0; i < 100 && rmdir(dir.c_str()) != 0 && errno == EBUSY; ++i) usleep(10000);
}

}  // namespace voxlab
