#pragma once
// What the benchmark programs share: the machine a result was measured on
// (its CPU, its load, the date), the process's memory, comma-separated
// option lists and medians. Results are committed with the machine named
// (STYLE.md point 15), so every program prints these the same way.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace sph::bench {

// The items of a comma-separated list ("egl,osmesa"), empty ones left out.
inline std::vector<std::string> split_list(const std::string& list) {
    std::vector<std::string> items;
    std::size_t from = 0;
    while (from <= list.size()) {
        const std::size_t to = std::min(list.find(',', from), list.size());
        if (to > from)
            items.push_back(list.substr(from, to - from));
        from = to + 1;
    }
    return items;
}

// The middle value (the upper of the two middle ones for an even count):
// the repeats' typical time, untouched by one slow repeat.
inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

// /proc/cpuinfo's model name, or "unknown CPU".
inline std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0)
            return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

// The 1, 5 and 15 minute load averages, "-1.00" each where unreadable: a
// shared machine's load moves wall times, so a result names it.
inline std::string load_average() {
    double load[3] = {-1, -1, -1};
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3)
            load[0] = load[1] = load[2] = -1;
        std::fclose(f);
    }
    return fmt::format("{:.2f} {:.2f} {:.2f}", load[0], load[1], load[2]);
}

// Now, as strftime's `format` gives it in UTC.
inline std::string now_utc(const char* format = "%Y-%m-%d %H:%M UTC") {
    const std::time_t now = std::time(nullptr);
    char text[64] = "";
    std::strftime(text, sizeof text, format, std::gmtime(&now));
    return text;
}

// A field of /proc/self/status in bytes (VmRSS: resident now, VmHWM: its
// peak); 0 if unreadable.
inline double status_bytes(const char* field) {
    std::ifstream in("/proc/self/status");
    const std::string key = std::string(field) + ":";
    for (std::string line; std::getline(in, line);)
        if (line.compare(0, key.size(), key) == 0)
            return std::atof(line.c_str() + key.size()) * 1024.0;
    return 0;
}

// The process's peak resident memory so far, MiB (llvmpipe's buffers and
// textures are host memory, so they count).
inline double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

// CPU time of the whole process, ms, every thread's (llvmpipe's rasteriser,
// OpenVDB's and OpenMP's workers): on a shared machine it moves much less
// with the others' load than wall time, and against wall time it says how
// many cores a step keeps busy.
inline double cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// The options the GL benchmarks (render, surface) share: --tiny (a quick
// run, for ctest), --csv FILE, --png FOLDER, --counts N,N and
// --backends egl,osmesa.
struct CommonOptions {
    bool tiny = false;
    std::string csv, png, counts, backends = "egl,osmesa";

    // Takes argv[k], and its value (k moves past it), when it is one of them.
    bool take(int& k, int argc, char** argv) {
        const std::string arg = argv[k];
        const bool has_value = k + 1 < argc;
        if (arg == "--tiny")
            tiny = true;
        else if (arg == "--csv" && has_value)
            csv = argv[++k];
        else if (arg == "--png" && has_value)
            png = argv[++k];
        else if (arg == "--counts" && has_value)
            counts = argv[++k];
        else if (arg == "--backends" && has_value)
            backends = argv[++k];
        else
            return false;
        return true;
    }

    // The particle counts: --counts', else `fallback`.
    std::vector<std::size_t> particle_counts(std::vector<std::size_t> fallback) const {
        if (counts.empty())
            return fallback;
        std::vector<std::size_t> out;
        for (const std::string& item : split_list(counts))
            out.push_back(std::stoul(item));
        return out;
    }
};

} // namespace sph::bench
