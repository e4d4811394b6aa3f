// The run's thread count by measurement (src/parallel/thread_count_tuner.*):
// fed step times from a model machine, it settles on the count that costs
// least, finds a competing job that starts mid-run, and leaves a single core
// alone.
#include "parallel/thread_count_tuner.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <functional>
#include <map>
#include <thread>

using sph::parallel::ThreadCountTuner;

namespace {

// Steps `count` steps of 1,000 particles, each costing `cost(threads, k)`
// seconds per particle-step; returns the steps taken at each thread count.
std::map<int, std::uint64_t> run(ThreadCountTuner& tuner, int count,
                                 const std::function<double(int, int)>& cost, int first = 0) {
    std::map<int, std::uint64_t> steps;
    for (int k = first; k < first + count; ++k) {
        const int threads = tuner.threads();
        tuner.record(1000 * cost(threads, k), 1000);
        ++steps[threads];
    }
    return steps;
}

// A step of 1,000 particle-steps at 1 us each (1 ms): 250 steps a window
// of the count kept, 100 a try.
constexpr double one_thread = 1e-6;

} // namespace

TEST_CASE("on a quiet machine the tuner keeps every core, trying fewer less and less often",
          "[parallel]") {
    ThreadCountTuner tuner(2);
    CHECK(tuner.threads() == 2);
    // 2 threads: 1.7x (the 2D flows on the quiet machine).
    const auto steps =
        run(tuner, 40000, [](int t, int) { return one_thread / (t == 2 ? 1.7 : 1); });
    CHECK(tuner.threads() == 2);
    CHECK(tuner.changes() == 0);
    // The tries at 1 thread: a short window each, spaced 4, 8, ... 128 windows.
    CHECK(steps.at(1) > 0);
    CHECK(double(steps.at(1)) / double(steps.at(2)) < 0.05);
}

TEST_CASE("with a busy process on the machine the tuner steps with fewer threads", "[parallel]") {
    ThreadCountTuner tuner(2);
    // 2 threads at 0.3x of 1 (one busy process on 2 cores, measured).
    const auto steps =
        run(tuner, 40000, [](int t, int) { return t == 2 ? one_thread / 0.3 : one_thread; });
    CHECK(tuner.threads() == 1);
    CHECK(tuner.changes() == 1);
    // Found after the first two windows; 2 threads tried again now and then.
    CHECK(double(steps.at(2)) / double(steps.at(1)) < 0.05);
}

TEST_CASE("on a busy machine a try of more threads that plainly loses ends early", "[parallel]") {
    ThreadCountTuner tuner(2);
    // 2 threads at 0.3x of 1: a step at 2 threads takes 3.3 ms, a whole try
    // window (0.1 s) 30 steps, a quarter of it 8.
    int at_two = 0, longest = 0, tries = 0;
    for (int k = 0; k < 40000; ++k) {
        const int threads = tuner.threads();
        tuner.record(1000 * (threads == 2 ? one_thread / 0.3 : one_thread), 1000);
        if (threads == 2) {
            ++at_two;
            continue;
        }
        // The first window (at 2 threads, before anything is kept) is whole.
        if (at_two > 0 && k > 100) {
            longest = std::max(longest, at_two);
            ++tries;
        }
        at_two = 0;
    }
    CHECK(tuner.threads() == 1);
    REQUIRE(tries >= 5);
    CHECK(longest <= 9);
}

TEST_CASE("a competing job that starts mid-run is found within a few windows", "[parallel]") {
    ThreadCountTuner tuner(2);
    const auto busy_from = 20000;
    const auto cost = [&](int t, int k) {
        if (k < busy_from)
            return one_thread / (t == 2 ? 1.7 : 1);
        return t == 2 ? one_thread / 0.3 : one_thread;
    };
    run(tuner, busy_from, cost);
    REQUIRE(tuner.threads() == 2);
    // Ten windows after the job starts: the window that got dearer by more
    // than the slowdown set off a try at once.
    run(tuner, 2500, cost, busy_from);
    CHECK(tuner.threads() == 1);
    // And when the job ends, 2 threads come back at a later try.
    const auto quiet_again = [](int t, int) {
        return one_thread / (t == 2 ? 1.7 : 1);
    };
    run(tuner, 40000, quiet_again, busy_from + 2500);
    CHECK(tuner.threads() == 2);
}

TEST_CASE("the tuner tries only the counts on its ladder and never more than the most",
          "[parallel]") {
    SECTION("one core: always 1") {
        ThreadCountTuner tuner(1);
        run(tuner, 5000, [](int, int) { return one_thread; });
        CHECK(tuner.threads() == 1);
        REQUIRE(tuner.uses().size() == 1);
        CHECK(tuner.uses()[0].threads == 1);
        CHECK(tuner.uses()[0].steps == 5000);
    }
    SECTION("8 cores, best at 4: 8, 4, 2, 1 only, settling on 4") {
        ThreadCountTuner tuner(8);
        const auto cost = [](int t, int) {
            REQUIRE((t == 8 || t == 4 || t == 2 || t == 1));
            return one_thread / (t == 8 ? 2.5 : t == 4 ? 3.2 : t == 2 ? 1.9 : 1);
        };
        run(tuner, 40000, cost);
        CHECK(tuner.threads() == 4);
        std::uint64_t total = 0;
        for (const auto& use : tuner.uses())
            total += use.steps;
        CHECK(total == 40000);
    }
}

TEST_CASE("with the kernel's count of free cores a busy machine costs no tries", "[parallel]") {
    // 2 threads at 0.3x of 1 while one other process runs.
    bool busy = true;
    const auto cost = [&](int t, int) {
        return busy && t == 2 ? one_thread / 0.3 : one_thread / (t == 2 ? 1.7 : 1);
    };
    int asked = 0;
    // The model kernel: one core taken by the other process while busy.
    ThreadCountTuner tuner(2, [&](int own) {
        ++asked;
        CHECK(own >= 1);
        return busy ? 1 : 2;
    });
    SECTION("busy from the start: one thread from the first step, 2 never tried") {
        CHECK(tuner.free_cores_known());
        CHECK(tuner.first_threads() == 1);
        const auto steps = run(tuner, 40000, cost);
        CHECK(steps.count(2) == 0);
        CHECK(tuner.threads() == 1);
        CHECK(tuner.tries_skipped() > 5);
        // ... and when the other process ends, 2 threads come back.
        busy = false;
        const int skipped = tuner.tries_skipped();
        run(tuner, 5000, cost, 40000);
        CHECK(tuner.threads() == 2);
        CHECK(tuner.tries_skipped() == skipped);
    }
    SECTION("a count that says the cores are free is still measured") {
        busy = false;
        ThreadCountTuner fooled(2, [](int) { return 2; });
        CHECK(fooled.first_threads() == 2);
        // The other process the count missed: 2 threads lose, 1 is kept.
        busy = true;
        const auto steps =
            run(fooled, 40000, [](int t, int) { return t == 2 ? one_thread / 0.3 : one_thread; });
        CHECK(fooled.threads() == 1);
        CHECK(double(steps.at(2)) / double(steps.at(1)) < 0.05);
    }
    CHECK(asked >= 1);
}

TEST_CASE("a kernel count that is unknown leaves the tuner measuring", "[parallel]") {
    ThreadCountTuner tuner(2, [](int) { return -1; });
    CHECK(tuner.first_threads() == 2);
    CHECK(!ThreadCountTuner(2).free_cores_known());
    const auto steps =
        run(tuner, 40000, [](int t, int) { return t == 2 ? one_thread / 0.3 : one_thread; });
    CHECK(tuner.threads() == 1);
    CHECK(tuner.tries_skipped() == 0);
    CHECK(steps.at(2) > 0);
}

TEST_CASE("this machine's free cores are known or plainly not", "[parallel]") {
    const auto free = sph::parallel::free_cores_of_this_machine();
    if (!free)
        return; // a cpuset or CPU quota: the tuner measures alone
    const int cores = int(std::thread::hardware_concurrency());
    const int count = free(1);
    CHECK(count >= 0);
    CHECK(count <= cores);
    CHECK(sph::parallel::runnable_threads() >= 1); // this thread at least
}
