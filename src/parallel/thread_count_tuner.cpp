#include "parallel/thread_count_tuner.hpp"

#include <algorithm>
#include <utility>

namespace sph::parallel {

ThreadCountTuner::ThreadCountTuner(int max_threads, Settings settings, FreeCores free_cores)
    : settings_(settings), free_cores_(std::move(free_cores)) {
    for (int t = std::max(max_threads, 1);; t /= 2) {
        ladder_.push_back(t);
        if (t == 1)
            break;
    }
    // Only this thread of ours runs yet: start on the cores left free.
    if (free_cores_)
        if (const int free = free_cores_(1); free >= 0)
            while (first_ + 1 < int(ladder_.size()) && ladder_[first_] > std::max(free, 1))
                ++first_;
    active_ = kept_ = first_;
    steps_.assign(ladder_.size(), 0);
    seconds_.assign(ladder_.size(), 0);
    interval_ = settings_.first_interval;
    // The first window is followed by a try: a machine busy from the start
    // that the kernel's count did not show is found after two windows.
    windows_since_try_ = interval_;
}

void ThreadCountTuner::record(double seconds, std::uint64_t particle_steps) {
    steps_[active_] += 1;
    seconds_[active_] += seconds;
    window_seconds_ += seconds;
    window_particle_steps_ += particle_steps;
    // Tries are short: on a busy machine a try of more threads is slow.
    const double length = trying_ || first_window_ ? settings_.try_window_s : settings_.window_s;
    const bool lost_early =
        trying_ && window_seconds_ >= settings_.abort_after * length &&
        window_seconds_ > settings_.abort_slowdown * kept_cost_ * double(window_particle_steps_);
    if (window_seconds_ < length && !lost_early)
        return;
    first_window_ = false;
    const double cost =
        window_seconds_ / double(std::max<std::uint64_t>(window_particle_steps_, 1));
    window_seconds_ = 0;
    window_particle_steps_ = 0;
    end_window(cost);
}

void ThreadCountTuner::end_window(double cost) {
    if (trying_) {
        trying_ = false;
        windows_since_try_ = 0;
        if (cost < kept_cost_ * (1 - settings_.margin)) {
            kept_ = active_;
            kept_cost_ = cost;
            interval_ = settings_.first_interval;
            ++changes_;
        } else {
            active_ = kept_;
            interval_ = std::min(2 * interval_, settings_.max_interval);
        }
        return;
    }
    // A dearer window sets off a try only some windows after the last one:
    // in a clip the frames' encoding takes a core now and then, and each
    // such window would otherwise be a try.
    const bool dearer = kept_cost_ > 0 && cost > settings_.slowdown * kept_cost_;
    kept_cost_ = cost;
    ++windows_since_try_;
    if (windows_since_try_ < interval_ &&
        !(dearer && windows_since_try_ >= settings_.first_interval))
        return;
    // The neighbour on the ladder, alternating sides where there are two.
    int index = kept_ + next_direction_;
    if (index < 0 || index >= int(ladder_.size()))
        index = kept_ - next_direction_;
    next_direction_ = -next_direction_;
    if (index < 0 || index >= int(ladder_.size()) || index == kept_)
        return;
    // More threads than the cores other work leaves free would wait for
    // them: ask again after as many windows, without measuring.
    if (ladder_[index] > ladder_[kept_] && free_cores_) {
        const int free = free_cores_(ladder_[kept_]);
        if (free >= 0 && free < ladder_[index]) {
            ++tries_skipped_;
            windows_since_try_ = 0;
            return;
        }
    }
    start_try(index);
}

void ThreadCountTuner::start_try(int index) {
    active_ = index;
    trying_ = true;
}

std::vector<ThreadCountTuner::Use> ThreadCountTuner::uses() const {
    std::vector<Use> used;
    for (std::size_t k = 0; k < ladder_.size(); ++k)
        if (steps_[k] > 0)
            used.push_back({ladder_[k], steps_[k], seconds_[k]});
    return used;
}

} // namespace sph::parallel
