// WorkerPool: every index exactly once, nested runs, thread reuse across runs, the
// serial cases, concurrent callers (also run under ThreadSanitizer: `make tsan`).
#include "sylva/core/base/WorkerPool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include <unistd.h>

namespace sylva {
namespace {

// Kernel thread ids: unlike std::thread::id they are not reused when a thread ends and
// another starts, so they count the threads that ever ran.
class ThreadIds {
public:
    void record() {
        const pid_t id = gettid();
        std::lock_guard lock(mutex_);
        ids_.insert(id);
    }
    std::set<pid_t> ids() {
        std::lock_guard lock(mutex_);
        return ids_;
    }

private:
    std::mutex mutex_;
    std::set<pid_t> ids_;
};

void expectEachOnce(const std::vector<std::atomic<int>>& calls) {
    for (std::size_t i = 0; i < calls.size(); ++i) {
        ASSERT_EQ(calls[i].load(), 1) << "index " << i;
    }
}

TEST(WorkerPool, EveryIndexRunsExactlyOnce) {
    WorkerPool pool(4);  // more threads than this machine's cores on purpose
    for (int grain : {1, 7, 1000, 5000}) {
        for (int count : {0, 1, 2, 3, 999, 10000}) {
            std::vector<std::atomic<int>> calls(static_cast<std::size_t>(count));
            pool.run(
                count, [&](int i) { calls[std::size_t(i)].fetch_add(1); }, grain);
            expectEachOnce(calls);
        }
    }
}

TEST(WorkerPool, SharedPoolRunsEveryIndexOnce) {
    EXPECT_EQ(WorkerPool::shared().threadCount(), std::min(WorkerPool::hardwareThreads(), 16));
    std::vector<std::atomic<int>> calls(4096);
    WorkerPool::shared().run(4096, [&](int i) { calls[std::size_t(i)].fetch_add(1); });
    expectEachOnce(calls);
}

// A body that runs a loop of its own (same pool, and the shared pool) completes, and the
// inner loop runs serially on the thread of the outer body.
TEST(WorkerPool, NestedRunCompletesOnTheBodysThread) {
    WorkerPool pool(3);
    for (WorkerPool* inner : {&pool, &WorkerPool::shared()}) {
        std::vector<std::atomic<int>> calls(8 * 100);
        std::atomic<int> foreign{0};
        pool.run(8, [&](int outer) {
            const pid_t self = gettid();
            inner->run(100, [&](int i) {
                calls[std::size_t(outer * 100 + i)].fetch_add(1);
                if (gettid() != self) {
                    foreign.fetch_add(1);
                }
                // Slow enough that idle threads would join a parallel inner loop.
                std::this_thread::sleep_for(std::chrono::microseconds(50));
            });
        });
        expectEachOnce(calls);
        EXPECT_EQ(foreign.load(), 0);
    }
}

// Many successive runs use the same threads: never more kernel threads than the pool
// has, where starting threads per run would show hundreds.
TEST(WorkerPool, SuccessiveRunsReuseTheSameThreads) {
    WorkerPool pool(3);
    ThreadIds ids;
    for (int run = 0; run < 200; ++run) {
        pool.run(6, [&](int) {
            ids.record();
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        });
    }
    const std::set<pid_t> seen = ids.ids();
    EXPECT_LE(seen.size(), 3u);
    EXPECT_GE(seen.size(), 2u);  // the workers took part (200 runs of sleeping bodies)
    EXPECT_TRUE(seen.count(gettid()));
}

TEST(WorkerPool, PoolOfOneRunsOnTheCaller) {
    WorkerPool pool(1);
    EXPECT_EQ(pool.threadCount(), 1);
    ThreadIds ids;
    std::vector<int> order;
    pool.run(1000, [&](int i) {
        ids.record();
        order.push_back(i);  // serial: no lock needed
    });
    EXPECT_EQ(ids.ids(), std::set<pid_t>{gettid()});
    ASSERT_EQ(order.size(), 1000u);
    for (int i = 0; i < 1000; ++i) {
        EXPECT_EQ(order[std::size_t(i)], i);
    }
}

// The Scheduler's workers: after runSeriallyOnThisThread every run stays on the thread.
TEST(WorkerPool, SerialThreadRunsOnItself) {
    WorkerPool pool(4);
    std::set<pid_t> seen;
    pid_t self = 0;
    std::thread thread([&] {
        WorkerPool::runSeriallyOnThisThread();
        self = gettid();
        ThreadIds ids;
        const auto body = [&](int) {
            ids.record();
            std::this_thread::sleep_for(std::chrono::microseconds(20));
        };
        pool.run(500, body);
        WorkerPool::shared().run(500, body);
        seen = ids.ids();
    });
    thread.join();
    EXPECT_EQ(seen, std::set<pid_t>{self});
}

// Several callers at once on one pool (the render thread and tile producers share the
// shared pool): every loop completes with each index once.
TEST(WorkerPool, ConcurrentCallersEachFinishTheirLoop) {
    WorkerPool pool(3);
    constexpr int kCallers = 4, kRuns = 50, kCount = 257;
    std::vector<std::vector<std::atomic<int>>> calls(kCallers);
    for (auto& c : calls) {
        c = std::vector<std::atomic<int>>(std::size_t(kRuns * kCount));
    }
    std::vector<std::thread> callers;
    for (int c = 0; c < kCallers; ++c) {
        callers.emplace_back([&, c] {
            for (int r = 0; r < kRuns; ++r) {
                pool.run(
                    kCount, [&](int i) { calls[std::size_t(c)][std::size_t(r * kCount + i)]++; },
                    1 + r % 5);
            }
        });
    }
    for (std::thread& t : callers) {
        t.join();
    }
    for (const auto& c : calls) {
        expectEachOnce(c);
    }
}

TEST(WorkerPoolDeathTest, ThrowingBodyIsAProgrammerError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    WorkerPool pool(1);
    EXPECT_DEATH(pool.run(3, [](int i) { throw i; }), "bodies must not throw");
}

}  // namespace
}  // namespace sylva
