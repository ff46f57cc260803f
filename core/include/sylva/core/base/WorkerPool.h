// WorkerPool: a fixed set of threads for data-parallel loops. run(count, body) calls
// body(i) exactly once for every i in [0, count), on the pool's threads and the calling
// thread, and returns when every call has returned.
//
// Threads are started once, at a pool's first parallel run, and live until the pool is
// destroyed; loops that run every frame (LodSelector) or every tile row (NoiseSource)
// therefore start no threads. WorkerPool::shared() is the process-wide pool of the
// machine's hardware threads; the plant LoD builder constructs pools of the size its
// --threads asks for.
//
// Serial cases: run() calls the bodies on the calling thread, in index order, when the
// pool has one thread, when there is only one block of items, when the caller is itself
// inside a pool's body (a nested run, of any pool: the outer run already occupies the
// threads, so nesting neither deadlocks nor oversubscribes the machine) and on threads
// that called runSeriallyOnThisThread().
//
// Several threads may call run() on one pool at once: each caller works on its own loop
// and returns when that loop is done; idle workers join the oldest open loop.
//
// Contract for bodies: they must not throw (an escaping exception is a programmer error:
// SYLVA_CHECK aborts with a message), and they must only write data of their own index
// (or synchronise themselves); results then never depend on the thread count.
#pragma once

#include <condition_variable>
#include <functional>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

namespace sylva {

class WorkerPool {
public:
    // A pool of `threads` threads in all, the caller of run() included (threads - 1
    // workers). threads <= 0: hardwareThreads().
    explicit WorkerPool(int threads);
    // Stops and joins the workers. No run() of this pool may be in progress.
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // The process-wide pool: hardwareThreads() threads, at most 16. Created at the first
    // call and never destroyed (its idle workers end with the process), so a run from
    // any thread or static destructor finds it valid.
    static WorkerPool& shared();
    // std::thread::hardware_concurrency(), at least 1.
    static int hardwareThreads();

    // Threads that may run bodies of one run(), the caller included.
    int threadCount() const { return threads_; }

    // Calls body(i) once for each i in [0, count) (count <= 0: nothing) and returns when
    // all calls have returned. Items are handed out dynamically in blocks of `grain`
    // consecutive indices (grain >= 1; a block runs in index order on one thread).
    void run(int count, const std::function<void(int)>& body, int grain = 1);

    // Makes every run() called on this thread from now on serial (any pool). The tile
    // Scheduler's workers call it: they already fill every core with whole tiles.
    static void runSeriallyOnThisThread();

private:
    struct Loop;
    void startWorkers();  // mutex_ held
    void workerMain();
    Loop* openLoop();  // mutex_ held: the oldest loop with unclaimed items, or null

    int threads_ = 1;
    std::mutex mutex_;
    std::condition_variable wake_;  // workers: a loop opened, or stopping_
    std::condition_variable done_;  // callers: a worker left a loop
    std::list<Loop*> loops_;        // open loops, oldest first (owned by their callers)
    std::vector<std::thread> workers_;
    bool stopping_ = false;
};

}  // namespace sylva
