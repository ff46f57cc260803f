#include "sylva/core/plantlod/PlantThreads.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace sylva {

int resolveThreadCount(int threads) {
    if (threads > 0) {
        return threads;
    }
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void runOnThreads(int count, int threads, const std::function<void(int)>& body) {
    const int workers = std::min(resolveThreadCount(threads), count);
    if (workers <= 1) {
        for (int i = 0; i < count; ++i) {
            body(i);
        }
        return;
    }
    std::atomic<int> next{0};
    const auto work = [&] {
        for (int i = next++; i < count; i = next++) {
            body(i);
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < workers; ++t) {
        pool.emplace_back(work);
    }
    work();
    for (std::thread& thread : pool) {
        thread.join();
    }
}

}  // namespace sylva
