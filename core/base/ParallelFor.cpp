#include "sylva/core/base/ParallelFor.h"

#include <algorithm>
#include <thread>
#include <vector>

namespace sylva {
namespace {
thread_local bool parallelForDisabled = false;
}  // namespace

void disableParallelForOnThisThread() {
    parallelForDisabled = true;
}

void parallelFor(int begin, int end, const std::function<void(int)>& body) {
    const int count = end - begin;
    if (count <= 0) {
        return;
    }
    const int threads =
        std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, std::min(count, 16));
    if (threads == 1 || parallelForDisabled) {
        for (int i = begin; i < end; ++i) {
            body(i);
        }
        return;
    }
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    const auto chunk = [&](int t) {
        const int from = begin + static_cast<int>(static_cast<long long>(count) * t / threads);
        const int to = begin + static_cast<int>(static_cast<long long>(count) * (t + 1) / threads);
        for (int i = from; i < to; ++i) {
            body(i);
        }
    };
    for (int t = 1; t < threads; ++t) {
        workers.emplace_back(chunk, t);
    }
    chunk(0);
    for (std::thread& worker : workers) {
        worker.join();
    }
}

}  // namespace sylva
