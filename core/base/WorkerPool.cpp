#include "sylva/core/base/WorkerPool.h"

#include <algorithm>
#include <atomic>
#include <cstdint>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

// True on pool workers (always) and on a run()'s caller while it runs bodies: a run()
// from such a thread is nested and runs serially.
thread_local bool insidePool = false;
// Set by runSeriallyOnThisThread().
thread_local bool serialThread = false;

void invoke(const std::function<void(int)>& body, int index) {
    try {
        body(index);
    } catch (...) {
        SYLVA_CHECK_MESSAGE(false, "a WorkerPool body threw an exception (bodies must not throw)");
    }
}

}  // namespace

// One run() in progress; lives on its caller's stack.
struct WorkerPool::Loop {
    const std::function<void(int)>* body = nullptr;
    int count = 0;
    int grain = 1;
    std::atomic<std::int64_t> next{0};  // first unclaimed index (64 bits: never wraps)
    int helpers = 0;                    // workers inside the loop (guarded by mutex_)

    bool open() const { return next.load(std::memory_order_relaxed) < count; }

    // Claims and runs blocks until none is left.
    void work() {
        for (;;) {
            const std::int64_t first = next.fetch_add(grain, std::memory_order_relaxed);
            if (first >= count) {
                return;
            }
            const int last = int(std::min<std::int64_t>(count, first + grain));
            for (int i = int(first); i < last; ++i) {
                invoke(*body, i);
            }
        }
    }
};

WorkerPool::WorkerPool(int threads) : threads_(threads > 0 ? threads : hardwareThreads()) {}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard lock(mutex_);
        SYLVA_CHECK_MESSAGE(loops_.empty(), "WorkerPool destroyed during a run()");
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& worker : workers_) {
        worker.join();
    }
}

WorkerPool& WorkerPool::shared() {
    static WorkerPool* pool = new WorkerPool(std::min(hardwareThreads(), 16));
    return *pool;
}

int WorkerPool::hardwareThreads() {
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void WorkerPool::runSeriallyOnThisThread() {
    serialThread = true;
}

void WorkerPool::run(int count, const std::function<void(int)>& body, int grain) {
    SYLVA_CHECK(grain >= 1);
    if (count <= 0) {
        return;
    }
    const std::int64_t blocks = (std::int64_t{count} + grain - 1) / grain;
    if (threads_ == 1 || blocks == 1 || insidePool || serialThread) {
        for (int i = 0; i < count; ++i) {
            invoke(body, i);
        }
        return;
    }
    Loop loop;
    loop.body = &body;
    loop.count = count;
    loop.grain = grain;
    const int helpers = int(std::min<std::int64_t>(threads_ - 1, blocks - 1));
    {
        std::lock_guard lock(mutex_);
        startWorkers();
        loops_.push_back(&loop);
    }
    if (helpers == threads_ - 1) {
        wake_.notify_all();
    } else {
        for (int h = 0; h < helpers; ++h) {
            wake_.notify_one();
        }
    }
    insidePool = true;
    loop.work();
    insidePool = false;
    // Every block is claimed; wait for the workers still running one. No worker joins
    // the loop any more (it is no longer open), and it leaves the list under the lock.
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return loop.helpers == 0; });
    loops_.remove(&loop);
}

void WorkerPool::startWorkers() {
    if (!workers_.empty()) {
        return;
    }
    workers_.reserve(std::size_t(threads_ - 1));
    for (int t = 1; t < threads_; ++t) {
        workers_.emplace_back([this] { workerMain(); });
    }
}

WorkerPool::Loop* WorkerPool::openLoop() {
    for (Loop* loop : loops_) {
        if (loop->open()) {
            return loop;
        }
    }
    return nullptr;
}

void WorkerPool::workerMain() {
    insidePool = true;
    std::unique_lock lock(mutex_);
    for (;;) {
        Loop* loop = nullptr;
        wake_.wait(lock, [&] { return stopping_ || (loop = openLoop()) != nullptr; });
        if (loop == nullptr) {
            return;  // stopping
        }
        ++loop->helpers;
        lock.unlock();
        loop->work();
        lock.lock();
        if (--loop->helpers == 0) {
            done_.notify_all();
        }
    }
}

}  // namespace sylva
