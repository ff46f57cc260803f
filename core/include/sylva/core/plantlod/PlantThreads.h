// runOnThreads: runs body(i) for i in [0, count) on `threads` threads (≤ 0: all cores),
// items handed out dynamically. The plant LoD builder runs restarts, views and samples
// through it; every item writes only its own outputs, so results never depend on the
// thread count (a fixed seed gives identical files with --threads 1 and 2).
#pragma once

#include <functional>

namespace sylva {

int resolveThreadCount(int threads);
void runOnThreads(int count, int threads, const std::function<void(int)>& body);

}  // namespace sylva
