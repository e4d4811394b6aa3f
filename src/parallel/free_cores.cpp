#include "parallel/free_cores.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sched.h>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>

namespace sph::parallel {

namespace {

// "0.30 0.10 0.03 2/250 1234": runnable / existing scheduling entities.
int read_runnable() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen, entities;
    if (!(in >> one >> five >> fifteen >> entities))
        return -1;
    const auto slash = entities.find('/');
    if (slash == std::string::npos)
        return -1;
    try {
        return std::stoi(entities.substr(0, slash));
    } catch (...) {
        return -1;
    }
}

// The cgroup paths of this process: "0::/path" (v2), "N:cpu,cpuacct:/path" (v1).
bool cpu_quota_applies() {
    std::ifstream cgroups("/proc/self/cgroup");
    std::string line;
    while (std::getline(cgroups, line)) {
        const auto first = line.find(':');
        const auto second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos)
            continue;
        const std::string controllers = line.substr(first + 1, second - first - 1);
        const std::string path = line.substr(second + 1);
        if (controllers.empty()) {
            // v2: "max 100000" when unlimited.
            std::ifstream max("/sys/fs/cgroup" + path + "/cpu.max");
            std::string quota;
            if (max >> quota && quota != "max")
                return true;
            continue;
        }
        std::stringstream names(controllers);
        std::string name;
        while (std::getline(names, name, ','))
            if (name == "cpu")
                for (const std::string mount : {"cpu", "cpu,cpuacct", "cpuacct,cpu"}) {
                    std::ifstream quota_file("/sys/fs/cgroup/" + mount + path +
                                             "/cpu.cfs_quota_us");
                    long quota = -1;
                    if (quota_file >> quota && quota > 0)
                        return true;
                }
    }
    return false;
}

} // namespace

int runnable_threads() {
    int least = -1;
    for (int sample = 0; sample < 3; ++sample) {
        if (sample > 0)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        const int runnable = read_runnable();
        if (runnable < 0)
            return -1;
        least = least < 0 ? runnable : std::min(least, runnable);
    }
    return least;
}

FreeCores free_cores_of_this_machine() {
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    cpu_set_t mask;
    CPU_ZERO(&mask);
    if (online < 1 || sched_getaffinity(0, sizeof(mask), &mask) != 0 ||
        CPU_COUNT(&mask) != online || cpu_quota_applies() || read_runnable() < 0)
        return {};
    return [cores = int(online)](int own) {
        const int runnable = runnable_threads();
        if (runnable < 0)
            return -1;
        // Our own threads may all be counted (the pool's threads spin a
        // while after a step), or fewer: subtracting all of them errs
        // toward more free cores, which the tuner then measures.
        return std::clamp(cores - std::max(runnable - own, 0), 0, cores);
    };
}

} // namespace sph::parallel
