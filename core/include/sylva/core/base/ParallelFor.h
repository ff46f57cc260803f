// parallelFor: runs body(i) for i in [begin, end) on up to hardware_concurrency
// threads, in contiguous chunks. For data-parallel loops inside one tile (noise
// synthesis dominates tile cost); the tile-level manager/worker Scheduler is separate.
// The body must not throw and must only touch data of its own index.
#pragma once

#include <functional>

namespace sylva {

void parallelFor(int begin, int end, const std::function<void(int)>& body);

// Makes parallelFor run serially on the calling thread from now on. The tile
// Scheduler's workers call it: they already occupy every core with whole tiles, and
// nested threads would only oversubscribe the machine.
void disableParallelForOnThisThread();

}  // namespace sylva
