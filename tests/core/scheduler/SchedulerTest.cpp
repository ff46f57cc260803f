#include "sylva/core/scheduler/FrameWantedSet.h"
#include "sylva/core/scheduler/Scheduler.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <numbers>
#include <random>
#include <thread>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace sylva {
namespace {

using namespace std::chrono_literals;

// Blocks produce() calls of gated sources until opened.
class Gate {
public:
    void open() {
        {
            std::lock_guard lock(mutex_);
            open_ = true;
        }
        wake_.notify_all();
    }
    void pass() {
        std::unique_lock lock(mutex_);
        ++waiting_;
        wake_.notify_all();
        wake_.wait(lock, [&] { return open_; });
    }
    void waitForWaiters(int count) {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return waiting_ >= count; });
    }

private:
    std::mutex mutex_;
    std::condition_variable wake_;
    bool open_ = false;
    int waiting_ = 0;
};

// A test source: value = sum of its inputs' values + tag + key.x, counted calls, an
// optional delay, failure, gate and a log of the keys produced (in order).
class TestSource final : public Source {
public:
    TestSource(std::string name, std::uint64_t tag, std::vector<const Source*> inputs = {})
        : Source(std::move(name), "test", PortType::Elevation, 1), tag_(tag) {
        for (const Source* input : inputs) {
            addInput(input);
        }
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        ++calls;
        if (gate != nullptr) {
            gate->pass();
        }
        {
            std::lock_guard lock(logMutex);
            log.push_back(key);
        }
        if (delay.count() > 0) {
            std::this_thread::sleep_for(delay);
        }
        if (fail) {
            return Error{"disk on fire"};
        }
        float value = float(tag_) + float(key.x);
        for (const Source* input : inputs()) {
            Result<TilePointer> in = provider.tile(*input, key);
            if (!in) {
                return in.error();
            }
            value += in.value()->at(0, 0, 0);
        }
        auto tile =
            std::make_shared<ImageTile>(key, provider.format().size, provider.format().border, 1);
        for (float& t : tile->texels()) {
            t = value;
        }
        return TilePointer(std::move(tile));
    }
    mutable std::atomic<int> calls{0};
    mutable std::mutex logMutex;
    mutable std::vector<TileKey> log;
    std::chrono::microseconds delay{0};
    bool fail = false;
    Gate* gate = nullptr;

private:
    std::uint64_t tag_;
};

SchedulerOptions options(int workers, std::size_t budget = 1u << 30) {
    SchedulerOptions result;
    result.format = TileFormat{8, 1};
    result.workers = workers;
    result.budgetBytes = budget;
    return result;
}

constexpr std::size_t kTileBytes = 10 * 10 * sizeof(float);  // 8² + 1-texel border

TEST(Scheduler, ConcurrentRequestsForOneTileProduceItOnce) {
    TestSource source("slow", 1);
    source.delay = 20ms;
    Scheduler scheduler(options(4));
    const TileKey key{3, 0, 5, 2};
    std::vector<std::thread> threads;
    std::atomic<int> correct{0};
    for (int i = 0; i < 8; ++i) {
        threads.emplace_back([&] {
            Result<TilePointer> tile = scheduler.tile(source, key);
            if (tile && tile.value()->at(0, 0, 0) == 6.0f) {
                ++correct;
            }
        });
    }
    for (int i = 0; i < 8; ++i) {
        scheduler.request(source, key, i);
        (void)scheduler.tryGet(source, key, 0);
    }
    for (std::thread& thread : threads) {
        thread.join();
    }
    scheduler.waitIdle();
    EXPECT_EQ(correct.load(), 8);
    EXPECT_EQ(source.calls.load(), 1);
    EXPECT_EQ(scheduler.totals().misses, 1u);
    EXPECT_GE(scheduler.totals().hits, 1u);
}

#if defined(__linux__)
// Seed 001 §4.6: workers run below the render (here: the test) thread in OS priority.
class NicenessSource final : public Source {
public:
    NicenessSource() : Source("niceness", "test", PortType::Elevation, 1) { setParameterHash(99); }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        niceness = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
        return TilePointer(std::make_shared<ImageTile>(key, provider.format().size, 0, 1));
    }
    mutable std::atomic<int> niceness{-100};
};

TEST(Scheduler, WorkersRunBelowTheCallersPriority) {
    NicenessSource source;
    SchedulerOptions settings = options(1);
    settings.workerNiceIncrement = 5;
    Scheduler scheduler(settings);
    const int caller = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
    scheduler.request(source, TileKey{1, 0, 0, 0}, 0);
    scheduler.waitIdle();
    EXPECT_EQ(source.niceness.load(), std::min(19, caller + 5));
}
#endif

TEST(Scheduler, OneWorkerRunsQueuedTasksInPriorityOrder) {
    TestSource blocker("blocker", 1);
    Gate gate;
    blocker.gate = &gate;
    TestSource source("ordered", 2);
    Scheduler scheduler(options(1));
    scheduler.request(blocker, TileKey{0, 0, 0, 0}, 0);
    gate.waitForWaiters(1);  // the only worker is busy now
    const int priorities[] = {7, 3, 9, 1, 5, 0, 8, 2, 6, 4};
    for (int i = 0; i < 10; ++i) {
        scheduler.request(source, TileKey{4, 0, i, 0}, priorities[i]);
    }
    while (scheduler.queuedTasks() < 10) {
        std::this_thread::sleep_for(1ms);
    }
    gate.open();
    scheduler.waitIdle();
    ASSERT_EQ(source.log.size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
        const int x = source.log[i].x;
        EXPECT_EQ(priorities[x], int(i)) << "position " << i;
    }
    EXPECT_EQ(Scheduler::priority(3, true), 3);
    EXPECT_LT(Scheduler::priority(20, true), Scheduler::priority(0, false));
}

TEST(Scheduler, CancelledQueuedTasksNeverRunAndRunningOnesAreCached) {
    TestSource running("running", 1);
    Gate gate;
    running.gate = &gate;
    TestSource queued("queued", 2);
    Scheduler scheduler(options(1));
    const TileKey key{2, 0, 1, 1};
    EXPECT_EQ(scheduler.tryGet(running, key, 0).state, TileLookup::State::Pending);
    gate.waitForWaiters(1);
    for (int i = 0; i < 6; ++i) {
        scheduler.request(queued, TileKey{3, 0, i, 0}, 1);
    }
    while (scheduler.queuedTasks() < 6) {
        std::this_thread::sleep_for(1ms);
    }
    scheduler.cancel(queued, TileKey{3, 0, 0, 0});
    scheduler.cancel(running, key);  // already running: finishes and is cached
    // The renderer's per-frame list keeps only x = 4 and 5 (and asks for x = 7).
    scheduler.setWanted({{&queued, TileKey{3, 0, 4, 0}, 1},
                         {&queued, TileKey{3, 0, 5, 0}, 1},
                         {&queued, TileKey{3, 0, 7, 0}, 1}});
    scheduler.setWanted({{&queued, TileKey{3, 0, 4, 0}, 1},
                         {&queued, TileKey{3, 0, 5, 0}, 1},
                         {&queued, TileKey{3, 0, 7, 0}, 1}});
    gate.open();
    scheduler.waitIdle();
    EXPECT_EQ(running.calls.load(), 1);
    const TileLookup lookup = scheduler.tryGet(running, key, 0);
    ASSERT_EQ(lookup.state, TileLookup::State::Ready);
    EXPECT_EQ(lookup.tile->at(0, 0, 0), 2.0f);
    std::vector<int> produced;
    for (const TileKey& k : queued.log) {
        produced.push_back(k.x);
    }
    std::sort(produced.begin(), produced.end());
    EXPECT_EQ(produced, (std::vector<int>{4, 5, 7}));
    scheduler.cancelAll();
    scheduler.waitIdle();
}

// The viewer's frames: the terrain posts its wanted list every frame, the vegetation
// stream asks for instance tiles with tryGet after it. A tile asked for again every
// frame survives the lists (it used to be cancelled by each one); a tile no longer asked
// for is cancelled at the second list after its last request.
TEST(Scheduler, RequestsOfAnotherClientSurviveWantedListsWhileAskedFor) {
    TestSource running("running", 1);
    Gate gate;
    running.gate = &gate;
    TestSource terrain("terrain", 2);
    TestSource instances("instances", 3);
    Scheduler scheduler(options(1));
    EXPECT_EQ(scheduler.tryGet(running, TileKey{2, 0, 1, 1}, 0).state, TileLookup::State::Pending);
    gate.waitForWaiters(1);
    const TileKey kept{4, 0, 1, 0};
    const TileKey dropped{4, 0, 2, 0};
    for (int frame = 0; frame < 4; ++frame) {
        scheduler.setWanted({{&terrain, TileKey{3, 0, frame, 0}, 1}});
        EXPECT_EQ(scheduler.tryGet(instances, kept, 40).state, TileLookup::State::Pending);
        if (frame == 0) {
            EXPECT_EQ(scheduler.tryGet(instances, dropped, 40).state, TileLookup::State::Pending);
        }
    }
    // The next frame's list comes before the stream asks again: the instance tile was
    // asked for since the previous list, so it stays queued (the old scheduler cancelled
    // it here, and a worker that had it dispatched skipped it).
    scheduler.setWanted({{&terrain, TileKey{3, 0, 4, 0}, 1}});
    scheduler.waitForMessages();
    EXPECT_EQ(scheduler.queuedTasks(), 2u);  // the last list's terrain tile and `kept`
    gate.open();
    scheduler.waitIdle();
    std::vector<int> produced;
    for (const TileKey& k : instances.log) {
        produced.push_back(k.x);
    }
    EXPECT_EQ(produced, std::vector<int>{1});
    std::vector<int> terrainProduced;
    for (const TileKey& k : terrain.log) {
        terrainProduced.push_back(k.x);
    }
    EXPECT_EQ(terrainProduced, std::vector<int>{4});  // only the last frame's list
}

// The same frames with a manager that keeps up: each message is handled before the next
// call, so the stream's repeated tryGet finds the task already held and posts nothing.
// The ask must still count (it used to be lost: the tile was cancelled two lists after
// it was first queued, queued again, cancelled again, and missing at the end).
TEST(Scheduler, RequestsHeldByTheManagerSurviveWantedListsWhileAskedFor) {
    TestSource running("running", 1);
    Gate gate;
    running.gate = &gate;
    TestSource terrain("terrain", 2);
    TestSource instances("instances", 3);
    Scheduler scheduler(options(1));
    EXPECT_EQ(scheduler.tryGet(running, TileKey{2, 0, 1, 1}, 0).state, TileLookup::State::Pending);
    gate.waitForWaiters(1);
    const TileKey kept{4, 0, 1, 0};
    const TileKey dropped{4, 0, 2, 0};
    for (int frame = 0; frame < 4; ++frame) {
        scheduler.setWanted({{&terrain, TileKey{3, 0, frame, 0}, 1}});
        scheduler.waitForMessages();
        EXPECT_EQ(scheduler.tryGet(instances, kept, 40).state, TileLookup::State::Pending);
        if (frame == 0) {
            EXPECT_EQ(scheduler.tryGet(instances, dropped, 40).state, TileLookup::State::Pending);
        }
        scheduler.waitForMessages();
    }
    scheduler.setWanted({{&terrain, TileKey{3, 0, 4, 0}, 1}});
    scheduler.waitForMessages();
    EXPECT_EQ(scheduler.queuedTasks(), 2u);  // the last list's terrain tile and `kept`
    gate.open();
    scheduler.waitIdle();
    std::vector<int> produced;
    for (const TileKey& k : instances.log) {
        produced.push_back(k.x);
    }
    EXPECT_EQ(produced, std::vector<int>{1});
}

// Records what reaches the wrapped provider: setWanted lists and tryGet calls; tiles of
// level 0 are "ready", the rest pending.
class RecordingProvider final : public TileProvider {
public:
    Result<TilePointer> tile(const Source&, const TileKey&) override { return Error{"unused"}; }
    const TileFormat& format() const override { return format_; }
    TileLookup tryGet(const Source&, const TileKey& key, int) override {
        ++tryGets;
        if (key.level == 0) {
            return {TileLookup::State::Ready, std::make_shared<ImageTile>(key, 8, 1, 1), {}};
        }
        return {};
    }
    void setWanted(const std::vector<TileRequest>& wanted) override { lists.push_back(wanted); }
    std::vector<std::vector<TileRequest>> lists;
    int tryGets = 0;

private:
    TileFormat format_{8, 1};
};

// One frame's clients (terrain list, canopy list, instance tiles by tryGet) reach the
// provider as one list: deduplicated by (source, key) with the smallest priority, most
// urgent first (ties in the order first asked for), ready tiles left out, and nothing
// before flush().
TEST(FrameWantedSet, MergesEveryClientOfAFrameIntoOneList) {
    TestSource terrain("terrain", 1);
    TestSource canopy("canopy", 2);
    TestSource instances("instances", 3);
    RecordingProvider provider;
    FrameWantedSet frame(provider);
    frame.setWanted({{&terrain, TileKey{3, 0, 0, 0}, 3}, {&terrain, TileKey{4, 0, 0, 0}, 4}});
    EXPECT_EQ(frame.tryGet(terrain, TileKey{3, 0, 0, 0}, 3).state, TileLookup::State::Pending);
    frame.setWanted({{&canopy, TileKey{3, 0, 0, 0}, 4}, {&terrain, TileKey{4, 0, 0, 0}, 2}});
    EXPECT_EQ(frame.tryGet(instances, TileKey{5, 0, 1, 0}, 3).state, TileLookup::State::Pending);
    EXPECT_EQ(frame.tryGet(instances, TileKey{0, 0, 1, 0}, 1).state, TileLookup::State::Ready);
    EXPECT_TRUE(provider.lists.empty());  // nothing cancelled mid-frame
    EXPECT_EQ(provider.tryGets, 3);       // answers come from the provider
    frame.flush();
    ASSERT_EQ(provider.lists.size(), 1u);
    const std::vector<TileRequest>& list = provider.lists[0];
    ASSERT_EQ(list.size(), 4u);
    EXPECT_EQ(list[0].source, &terrain);  // level 4, priority lowered to 2 by the second ask
    EXPECT_EQ(list[0].key, (TileKey{4, 0, 0, 0}));
    EXPECT_EQ(list[0].priority, 2);
    EXPECT_EQ(list[1].source, &terrain);  // priority 3, asked before the instance tile
    EXPECT_EQ(list[1].key, (TileKey{3, 0, 0, 0}));
    EXPECT_EQ(list[2].source, &instances);
    EXPECT_EQ(list[2].priority, 3);
    EXPECT_EQ(list[3].source, &canopy);
    EXPECT_EQ(list[3].priority, 4);
    frame.flush();  // a new frame starts empty
    ASSERT_EQ(provider.lists.size(), 2u);
    EXPECT_TRUE(provider.lists[1].empty());
}

// With the Scheduler: frame after frame the terrain, the canopy and the instance tiles
// go through one FrameWantedSet; none cancels another's queued tiles (each clipmap's own
// setWanted used to cancel the other's every frame), and the one worker runs them in the
// merged priority order: the near instance tile (2), the terrain (3), the canopy (4).
TEST(FrameWantedSet, NoClientCancelsAnotherAndTheSchedulerFollowsTheMergedOrder) {
    TestSource running("running", 1);
    Gate gate;
    running.gate = &gate;
    TestSource tiles("tiles", 2);  // one source, so one log shows the order across clients
    Scheduler scheduler(options(1));
    EXPECT_EQ(scheduler.tryGet(running, TileKey{2, 0, 1, 1}, 0).state, TileLookup::State::Pending);
    gate.waitForWaiters(1);
    const std::vector<TileRequest> terrainList = {{&tiles, TileKey{3, 0, 0, 0}, 3},
                                                  {&tiles, TileKey{3, 0, 1, 0}, 3}};
    const std::vector<TileRequest> canopyList = {{&tiles, TileKey{4, 0, 0, 0}, 4}};
    for (int frameIndex = 0; frameIndex < 3; ++frameIndex) {
        FrameWantedSet frame(scheduler);
        frame.setWanted(terrainList);
        frame.setWanted(canopyList);
        EXPECT_EQ(frame.tryGet(tiles, TileKey{5, 0, 0, 0}, 2).state, TileLookup::State::Pending);
        frame.flush();
    }
    for (int i = 0, steady = 0; i < 5000 && steady < 100; ++i) {
        steady = scheduler.queuedTasks() == 4 ? steady + 1 : 0;
        std::this_thread::sleep_for(1ms);
    }
    EXPECT_EQ(scheduler.queuedTasks(), 4u);
    gate.open();
    scheduler.waitIdle();
    std::vector<int> levels;
    for (const TileKey& k : tiles.log) {
        levels.push_back(k.level);
    }
    EXPECT_EQ(levels, (std::vector<int>{5, 3, 3, 4}));
}

TEST(Scheduler, FailureIsReportedOnceAndRepeatedWithoutRetry) {
    TestSource broken("broken", 1);
    broken.fail = true;
    TestSource user("user", 2, {&broken});
    std::mutex reportsMutex;
    std::vector<std::string> reports;
    SchedulerOptions settings = options(2);
    settings.failureSink = [&](const Error& error) {
        std::lock_guard lock(reportsMutex);
        reports.push_back(error.message);
    };
    Scheduler scheduler(settings);
    const TileKey key{1, 0, 2, 1};
    scheduler.request(broken, key, 0);
    scheduler.waitIdle();
    for (int i = 0; i < 5; ++i) {
        const TileLookup lookup = scheduler.tryGet(broken, key, 0);
        ASSERT_EQ(lookup.state, TileLookup::State::Failed);
        EXPECT_NE(lookup.error.message.find("disk on fire"), std::string::npos);
        EXPECT_NE(lookup.error.message.find("source 'broken'"), std::string::npos);
        Result<TilePointer> blocking = scheduler.tile(broken, key);
        ASSERT_FALSE(blocking);
        EXPECT_EQ(blocking.error().message, lookup.error.message);
    }
    Result<TilePointer> dependent = scheduler.tile(user, key);
    ASSERT_FALSE(dependent);
    EXPECT_NE(dependent.error().message.find("disk on fire"), std::string::npos);
    (void)scheduler.tile(user, key);
    EXPECT_EQ(broken.calls.load(), 1);
    EXPECT_EQ(user.calls.load(), 1);
    std::lock_guard lock(reportsMutex);
    ASSERT_EQ(reports.size(), 2u);  // the broken tile and its dependent, once each
    EXPECT_EQ(scheduler.totals().failures, 2u);
}

// The viewer redraws a still view only when finishedTasks() changed: it counts every
// task that finished (produced, nested inputs included, or failed), not cache hits.
TEST(Scheduler, FinishedTasksCountsEveryProducedOrFailedTile) {
    TestSource base("base", 1);
    TestSource top("top", 2, {&base});
    TestSource broken("broken", 3);
    broken.fail = true;
    Scheduler scheduler(options(2));
    EXPECT_EQ(scheduler.finishedTasks(), 0u);
    for (int x = 0; x < 3; ++x) {
        scheduler.request(top, TileKey{2, 0, x, 1}, 0);  // each also produces base's tile
    }
    scheduler.request(broken, TileKey{2, 0, 0, 1}, 0);
    scheduler.waitIdle();
    EXPECT_EQ(scheduler.finishedTasks(), 7u);
    for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(scheduler.tryGet(top, TileKey{2, 0, x, 1}, 0).state, TileLookup::State::Ready);
    }
    (void)scheduler.tile(top, TileKey{2, 0, 0, 1});
    EXPECT_EQ(scheduler.finishedTasks(), 7u) << "cache hits finish no task";
    (void)scheduler.tile(top, TileKey{2, 0, 5, 1});
    EXPECT_EQ(scheduler.finishedTasks(), 9u);
}

TEST(Scheduler, NestedDependenciesWithManyWorkersNeverDeadlock) {
    // A diamond chain: every top tile needs the same few shared inputs at each depth,
    // with more workers than cores and requests from several threads at once.
    TestSource base("base", 1);
    base.delay = 200us;
    TestSource left("left", 2, {&base});
    TestSource right("right", 3, {&base});
    TestSource top("top", 4, {&left, &right, &base});
    Scheduler scheduler(options(8));
    std::vector<TileRequest> wanted;
    for (int x = 0; x < 16; ++x) {
        wanted.push_back({&top, TileKey{4, 0, x, 3}, x});
    }
    scheduler.setWanted(wanted);
    std::vector<std::thread> clients;
    for (int c = 0; c < 4; ++c) {
        clients.emplace_back([&, c] {
            for (int x = 15 - c; x >= 0; x -= 2) {
                Result<TilePointer> tile = scheduler.tile(top, TileKey{4, 0, x, 3});
                ASSERT_TRUE(tile);
                // top = 4 + x + (2 + x + base) + (3 + x + base) + base, base = 1 + x
                EXPECT_EQ(tile.value()->at(0, 0, 0), float(12 + 6 * x));
            }
        });
    }
    for (std::thread& client : clients) {
        client.join();
    }
    scheduler.waitIdle();
    EXPECT_EQ(base.calls.load(), 16);
    EXPECT_EQ(left.calls.load(), 16);
    EXPECT_EQ(right.calls.load(), 16);
    EXPECT_EQ(top.calls.load(), 16);
}

TEST(Scheduler, CachedBytesStayWithinTheBudgetPlusOneTilePerWorker) {
    TestSource base("base", 1);
    TestSource derived("derived", 2, {&base});
    const std::size_t budget = 20 * kTileBytes;
    const int workers = 3;
    Scheduler scheduler(options(workers, budget));
    for (int round = 0; round < 4; ++round) {
        std::vector<TileRequest> wanted;
        for (int x = 0; x < 64; ++x) {
            wanted.push_back({&derived, TileKey{6, 0, x + round * 7, 10}, x});
        }
        scheduler.setWanted(wanted);
        scheduler.waitIdle();
    }
    EXPECT_LE(scheduler.peakCachedBytes(), budget + workers * kTileBytes);
    EXPECT_GT(scheduler.peakCachedBytes(), budget / 2);
    const SchedulerStatistics totals = scheduler.totals();
    EXPECT_LE(totals.bytes, budget);
    EXPECT_GT(totals.evictions, 0u);
    EXPECT_EQ(totals.bytes, totals.tiles * kTileBytes);
    const std::vector<SchedulerStatistics> perSource = scheduler.statisticsPerSource();
    ASSERT_EQ(perSource.size(), 2u);
    EXPECT_EQ(perSource[0].name, "base");
    EXPECT_EQ(perSource[1].name, "derived");
    EXPECT_EQ(perSource[0].misses + perSource[1].misses, totals.misses);
}

TEST(Scheduler, FocusDistanceCountsRingsAroundTheQuad) {
    // Level 3, k 0: 16 x 8 tiles of 22.5°. Focus at lon -180 + 22.5 * 5.3, lat 90 - 22.5 * 2.7.
    const double degree = std::numbers::pi / 180;
    const double longitude = (-180 + 22.5 * 5.3) * degree, latitude = (90 - 22.5 * 2.7) * degree;
    // fx = 5.3: quad columns 4..5; fy = 2.7: quad rows 2..3.
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 4, 2}, latitude, longitude), 0);
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 5, 3}, latitude, longitude), 0);
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 6, 3}, latitude, longitude), 1);
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 3, 1}, latitude, longitude), 1);
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 5, 6}, latitude, longitude), 3);
    // Across the antimeridian: column 15 is next to column 0.
    const double west = (-180 + 22.5 * 0.2) * degree;
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 15, 2}, latitude, west), 0);
    EXPECT_EQ(Scheduler::focusDistance({3, 0, 14, 2}, latitude, west), 1);
}

TEST(Scheduler, PruningKeepsTheRingAroundTheFocus) {
    TestSource source("grid", 1);
    const std::size_t budget = 30 * kTileBytes;
    Scheduler scheduler(options(1, budget));
    // Level 4: 32 x 16 tiles. Focus in tile (10.3, 7.4): quad x 9..10, y 6..7; the
    // ring adjacent to it is x 8..11, y 5..8 (16 tiles in all).
    const double longitude = (10.3 / 32) * 2 * std::numbers::pi - std::numbers::pi;
    const double latitude = std::numbers::pi / 2 - 7.4 / 16 * std::numbers::pi;
    scheduler.setFocus(latitude, longitude);
    // Touch the ring first, then many far tiles (more recently used than the ring).
    for (int y = 5; y <= 8; ++y) {
        for (int x = 8; x <= 11; ++x) {
            ASSERT_TRUE(scheduler.tile(source, TileKey{4, 0, x, y}));
        }
    }
    for (int y = 0; y < 16; ++y) {
        for (int x = 16; x < 32; ++x) {
            ASSERT_TRUE(scheduler.tile(source, TileKey{4, 0, x, y}));
        }
    }
    EXPECT_LE(scheduler.totals().bytes, budget);
    const int callsBefore = source.calls.load();
    for (int y = 5; y <= 8; ++y) {
        for (int x = 8; x <= 11; ++x) {
            const TileLookup lookup = scheduler.tryGet(source, TileKey{4, 0, x, y}, 0);
            EXPECT_EQ(lookup.state, TileLookup::State::Ready) << x << "," << y;
        }
    }
    scheduler.waitIdle();
    EXPECT_EQ(source.calls.load(), callsBefore);
    // Without a focus: least recently used goes first.
    Scheduler lru(options(1, 4 * kTileBytes));
    for (int x = 0; x < 6; ++x) {
        ASSERT_TRUE(lru.tile(source, TileKey{4, 0, x, 0}));
    }
    EXPECT_EQ(lru.tryGet(source, TileKey{4, 0, 5, 0}, 0).state, TileLookup::State::Ready);
    EXPECT_EQ(lru.tryGet(source, TileKey{4, 0, 2, 0}, 0).state, TileLookup::State::Ready);
    lru.cancelAll();
    EXPECT_EQ(lru.tryGet(source, TileKey{4, 0, 0, 0}, 0).state, TileLookup::State::Pending);
    lru.cancelAll();
    lru.waitIdle();
}

TEST(Scheduler, AFrameReadingTilesFarFromTheFocusKeepsThemWhileOlderTilesGo) {
    // Issue 17's thrash in small: a frame builds buildings whose ground tiles lie far from
    // the focus (the clipmap's centre) and reads them in turn, as GroundSampler does,
    // with the cache full of the previous frame's tiles near the focus. Pruning by
    // distance first evicted each ground tile right after it was produced (it was the
    // farthest), so every read produced it again.
    TestSource terrain("terrain", 1);
    TestSource ground("ground", 2);
    constexpr int kNear = 8;
    Scheduler scheduler(options(1, kNear * kTileBytes));
    // Level 6: 128 x 64 tiles; focus in tile (40.5, 20.5).
    const double longitude = (40.5 / 128) * 2 * std::numbers::pi - std::numbers::pi;
    const double latitude = std::numbers::pi / 2 - 20.5 / 64 * std::numbers::pi;
    scheduler.setFocus(latitude, longitude);
    scheduler.setWanted({});  // frame 1: the clipmap's tiles around the focus
    for (int x = 0; x < kNear; ++x) {
        ASSERT_TRUE(scheduler.tile(terrain, TileKey{6, 0, 38 + x % 4, 19 + x / 4}));
    }
    ASSERT_EQ(scheduler.totals().evictions, 0u);
    scheduler.setWanted({});  // frame 2: four ground tiles 60 columns away, read in turn
    for (int pass = 0; pass < 10; ++pass) {
        for (int x = 0; x < 4; ++x) {
            Result<TilePointer> tile = scheduler.tile(ground, TileKey{6, 0, 100 + x, 20});
            ASSERT_TRUE(tile);
            EXPECT_EQ(tile.value()->at(0, 0, 0), float(2 + 100 + x));
        }
    }
    EXPECT_EQ(ground.calls.load(), 4);
    EXPECT_LE(scheduler.totals().bytes, kNear * kTileBytes);
    // The older frame's tiles went instead (four of them, farthest first).
    EXPECT_EQ(scheduler.totals().evictions, 4u);
    // The next frame: the ground tiles are now an earlier frame's, farthest from the
    // focus, and go first.
    scheduler.setWanted({});
    ASSERT_TRUE(scheduler.tile(terrain, TileKey{6, 0, 40, 21}));
    EXPECT_EQ(scheduler.tryGet(ground, TileKey{6, 0, 100, 20}, 0).state, TileLookup::State::Ready);
    EXPECT_EQ(scheduler.tryGet(ground, TileKey{6, 0, 103, 20}, 0).state,
              TileLookup::State::Pending);
    scheduler.cancelAll();
    scheduler.waitIdle();
}

// Reads tile x = 0 of its input, then `others` more tiles of it, then x = 0 again (as a
// GroundSampler does when a building straddles two ground tiles).
class RereadingSource final : public Source {
public:
    RereadingSource(const Source* input, int others)
        : Source("rereading", "test", PortType::Elevation, 1), others_(others) {
        addInput(input);
        setParameterHash(std::uint64_t(others));
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        float sum = 0;
        for (int i = 0; i <= others_ + 1; ++i) {
            const int x = i <= others_ ? i : 0;
            Result<TilePointer> in = provider.tile(*inputs()[0], TileKey{key.level, 0, x, key.y});
            if (!in) {
                return in.error();
            }
            sum += in.value()->at(0, 0, 0);
        }
        auto tile =
            std::make_shared<ImageTile>(key, provider.format().size, provider.format().border, 1);
        for (float& t : tile->texels()) {
            t = sum;
        }
        return TilePointer(std::move(tile));
    }

private:
    int others_;
};

TEST(Scheduler, InputsOfARunningTaskAreNotEvictedBeforeItEnds) {
    // The task reads 9 distinct input tiles with room for 4: least recently used pruning
    // evicted tile 0 before the task read it again, so it was produced twice.
    TestSource base("base", 1);
    const RereadingSource reader(&base, 8);
    const std::size_t budget = 4 * kTileBytes;
    Scheduler scheduler(options(1, budget));
    Result<TilePointer> tile = scheduler.tile(reader, TileKey{5, 0, 3, 7});
    ASSERT_TRUE(tile);
    float expected = 0;
    for (int i = 0; i <= 9; ++i) {
        expected += float(1 + (i <= 8 ? i : 0));
    }
    EXPECT_EQ(tile.value()->at(0, 0, 0), expected);
    EXPECT_EQ(base.calls.load(), 9);
    // Pinned, the inputs exceeded the budget while the task ran; released, they went.
    EXPECT_GE(scheduler.peakCachedBytes(), 9 * kTileBytes);
    EXPECT_LE(scheduler.totals().bytes, budget);
    // Pins are per task: the same reads from outside a task are not pinned.
    const std::size_t evictionsBefore = scheduler.totals().evictions;
    for (int x = 0; x <= 8; ++x) {
        ASSERT_TRUE(scheduler.tile(base, TileKey{5, 0, x, 7}));
    }
    EXPECT_LE(scheduler.totals().bytes, budget);
    EXPECT_GT(scheduler.totals().evictions, evictionsBefore);
}

TEST(Scheduler, TaskReportsCountTheInputsAWorkerProducedWithinItsTask) {
    // A task whose inputs are not cached holds its worker while it produces them all:
    // the report (and runningTasks() meanwhile) says which task and how many inputs.
    TestSource base("base", 1);
    const RereadingSource reader(&base, 8);
    Gate gate;
    TestSource gated("gated", 2);
    gated.gate = &gate;
    std::mutex mutex;
    std::vector<SchedulerTaskReport> reports;
    SchedulerOptions withSink = options(1);
    withSink.taskSink = [&](const SchedulerTaskReport& report) {
        std::lock_guard lock(mutex);
        reports.push_back(report);
    };
    Scheduler scheduler(withSink);
    scheduler.request(reader, TileKey{5, 0, 3, 7}, 0);
    scheduler.waitIdle();
    scheduler.request(gated, TileKey{5, 0, 1, 1}, 0);
    gate.waitForWaiters(1);
    const std::vector<SchedulerTaskReport> running = scheduler.runningTasks();
    ASSERT_EQ(running.size(), 1u);
    EXPECT_EQ(running[0].source, "gated");
    EXPECT_EQ(running[0].key, (TileKey{5, 0, 1, 1}));
    EXPECT_GE(running[0].seconds, 0.0);
    gate.open();
    scheduler.waitIdle();
    EXPECT_TRUE(scheduler.runningTasks().empty());
    std::lock_guard lock(mutex);
    ASSERT_EQ(reports.size(), 2u);
    EXPECT_EQ(reports[0].source, "rereading");
    EXPECT_EQ(reports[0].key, (TileKey{5, 0, 3, 7}));
    EXPECT_EQ(reports[0].produced, 9u);  // 9 distinct inputs, the re-read one cached
    EXPECT_EQ(reports[0].producedPerSource.at("base"), 9u);
    EXPECT_EQ(reports[0].diskReads, 0u);
    EXPECT_FALSE(reports[0].fromDisk);
    EXPECT_EQ(reports[1].source, "gated");
    EXPECT_EQ(reports[1].produced, 0u);
    // Inputs produced by the render thread's own tile() are no worker's task.
    ASSERT_TRUE(scheduler.tile(reader, TileKey{5, 0, 4, 8}));
    EXPECT_EQ(reports.size(), 2u);
}

TEST(Scheduler, AnEditOverBudgetRecomputesTheEditedBranchNotTheEvictedExpensiveTiles) {
    // The turnaround bench's warm edit in small (issue 22: edit_ratio 0.155 -> 0.56):
    // one frame's tiles exceed the budget; `saturation` of the adjust branch changes.
    // hills (slow noise) -> height; raster -> adjust -> colour <- markers <- hills.
    // Least-recently-used pruning evicted the first keys' noise tiles during the frame,
    // so the edit computed them again; cost-aware pruning (GreedyDual-Size) evicts the
    // cheap tiles and the edit recomputes the edited branch and cheap tiles only.
    TestSource hills("hills", 1);
    hills.delay = 100ms;  // vs microseconds: far apart even on a loaded machine
    TestSource height("height", 2, {&hills});
    TestSource raster("raster", 3);
    TestSource markers("markers", 4, {&hills});
    TestSource adjust("adjust", 5, {&raster});
    TestSource colour("colour", 6, {&adjust, &markers});
    constexpr int kKeys = 8;
    // Room for the noise tiles and 12 of the 40 others.
    Scheduler scheduler(options(1, (kKeys + 12) * kTileBytes));
    const auto frame = [&](const Source& shown) {
        for (int x = 0; x < kKeys; ++x) {
            const TileKey key{4, 0, x, 3};
            ASSERT_TRUE(scheduler.tile(height, key));
            Result<TilePointer> tile = scheduler.tile(shown, key);
            ASSERT_TRUE(tile);
        }
    };
    frame(colour);
    ASSERT_EQ(hills.calls.load(), kKeys);
    ASSERT_GT(scheduler.totals().evictions, 0u);

    TestSource adjusted("adjust", 50, {&raster});  // the edit: a new content hash
    TestSource recoloured("colour", 6, {&adjusted, &markers});
    ASSERT_NE(recoloured.contentHash(), colour.contentHash());
    scheduler.retainOnly({hills.contentHash(), height.contentHash(), raster.contentHash(),
                          markers.contentHash(), adjusted.contentHash(), recoloured.contentHash()});
    frame(recoloured);
    EXPECT_EQ(hills.calls.load(), kKeys);  // no noise tile computed again
    EXPECT_EQ(adjusted.calls.load(), kKeys);
    EXPECT_EQ(recoloured.calls.load(), kKeys);
    EXPECT_LE(scheduler.totals().bytes, (kKeys + 12) * kTileBytes);
    for (int x = 0; x < kKeys; ++x) {
        const TileKey key{4, 0, x, 3};
        EXPECT_EQ(scheduler.tile(recoloured, key).value()->at(0, 0, 0),
                  float(6 + x) + float(50 + x) + float(3 + x) + float(4 + x) + float(1 + x));
    }
}

// A reload builds new Source objects, also for unchanged nodes (same hash): after
// retainOnly nothing asked of the old objects runs any more (a worker would use a
// destroyed object: issue 20's village walker test crashed so), and the task running
// when it was called, of a live hash, finished before it returned and is kept.
TEST(Scheduler, RetainOnlyForgetsEveryTaskOfTheOldObjectsAndWaitsForTheRunningOne) {
    Gate gate;
    auto old = std::make_unique<TestSource>("terrain", 1);
    old->gate = &gate;
    Scheduler scheduler(options(1));
    for (int x = 0; x < 6; ++x) {
        scheduler.request(*old, TileKey{4, 0, x, 3}, x);
    }
    gate.waitForWaiters(1);  // the first runs, held at the gate; five are queued
    std::thread opener([&] {
        std::this_thread::sleep_for(50ms);
        gate.open();
    });
    TestSource renewed("terrain", 1);
    ASSERT_EQ(renewed.contentHash(), old->contentHash());
    scheduler.retainOnly({renewed.contentHash()});
    EXPECT_EQ(scheduler.tryGet(renewed, TileKey{4, 0, 0, 3}, 0).state, TileLookup::State::Ready);
    opener.join();
    std::this_thread::sleep_for(100ms);  // time for a worker to take a forgotten task
    EXPECT_EQ(old->calls.load(), 1);
    old.reset();  // the old graph goes
    scheduler.waitIdle();
    ASSERT_TRUE(scheduler.tile(renewed, TileKey{4, 0, 5, 3}));
    EXPECT_EQ(renewed.calls.load(), 1);
}

TEST(Scheduler, InvalidationDropsTheNodeAndItsDependentsOnly) {
    TestSource terrain("terrain", 1);
    TestSource colour("colour", 2);
    TestSource normals("normals", 3, {&terrain});
    TestSource shaded("shaded", 4, {&normals, &colour});
    Scheduler scheduler(options(2));
    const TileKey key{2, 0, 3, 1};
    ASSERT_TRUE(scheduler.tile(shaded, key));
    const std::vector<std::uint64_t> dropped = scheduler.invalidate(terrain.contentHash());
    EXPECT_EQ(dropped.size(), 3u);  // terrain, normals, shaded
    ASSERT_TRUE(scheduler.tile(shaded, key));
    EXPECT_EQ(terrain.calls.load(), 2);
    EXPECT_EQ(normals.calls.load(), 2);
    EXPECT_EQ(shaded.calls.load(), 2);
    EXPECT_EQ(colour.calls.load(), 1);  // unchanged branch: still cached

    // A reload where only `colour` changed: new colour and shaded nodes, old ones go.
    TestSource colour2("colour", 20);
    TestSource shaded2("shaded", 4, {&normals, &colour2});
    ASSERT_NE(shaded2.contentHash(), shaded.contentHash());
    scheduler.retainOnly({terrain.contentHash(), normals.contentHash(), colour2.contentHash(),
                          shaded2.contentHash()});
    ASSERT_TRUE(scheduler.tile(shaded2, key));
    EXPECT_EQ(terrain.calls.load(), 2);
    EXPECT_EQ(normals.calls.load(), 2);
    EXPECT_EQ(colour2.calls.load(), 1);
    EXPECT_EQ(shaded2.calls.load(), 1);
    EXPECT_EQ(scheduler.statisticsPerSource().size(), 4u);
    // The old shaded node's tiles are gone: asking again produces it again.
    ASSERT_TRUE(scheduler.tile(shaded, key));
    EXPECT_EQ(shaded.calls.load(), 3);
    EXPECT_EQ(colour.calls.load(), 2);
}

TEST(Scheduler, StressRandomFocusRequestsCancelsAndInvalidations) {
    // Real threads for >= 10 s: a render thread moving the focus and handing wanted
    // lists, a blocking reader, invalidations and budget changes. Checked: every tile
    // returned has the right value, nothing deadlocks, the budget holds.
    TestSource base("base", 1);
    base.delay = 50us;
    TestSource detail("detail", 2);
    TestSource mid("mid", 3, {&base});
    TestSource top("top", 4, {&mid, &detail, &base});
    const int workers = 3;
    const std::size_t budget = 200 * kTileBytes;
    std::atomic<int> failures{0};
    SchedulerOptions settings = options(workers, budget);
    settings.failureSink = [&](const Error&) { ++failures; };
    Scheduler scheduler(settings);
    const auto expected = [](int x) { return float(4 + x + (3 + x + 1 + x) + (2 + x) + (1 + x)); };
    std::atomic<bool> stop{false};
    std::atomic<long> checked{0}, wrong{0};
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    std::thread reader([&] {
        std::mt19937 random(7);
        while (!stop) {
            const int level = 3 + int(random() % 4);
            const TileKey key{level, 0, int(random() % TileKey::columns(level, 0)),
                              int(random() % TileKey::rows(level))};
            Result<TilePointer> tile = scheduler.tile(top, key);
            if (!tile || tile.value()->at(1, 1, 0) != expected(key.x)) {
                ++wrong;
            }
            ++checked;
        }
    });
    std::mt19937 random(11);
    double latitude = 0.3, longitude = 1.0;
    long frames = 0;
    while (std::chrono::steady_clock::now() < deadline) {
        latitude = std::clamp(latitude + (int(random() % 201) - 100) * 1e-3, -1.4, 1.4);
        longitude =
            std::remainder(longitude + (int(random() % 201) - 100) * 2e-3, 2 * std::numbers::pi);
        scheduler.setFocus(latitude, longitude);
        std::vector<TileRequest> wanted;
        for (int level = 2; level <= 7; ++level) {
            const int columns = TileKey::columns(level, 0), rows = TileKey::rows(level);
            const int fx = int((longitude + std::numbers::pi) / (2 * std::numbers::pi) * columns);
            const int fy = int((std::numbers::pi / 2 - latitude) / std::numbers::pi * rows);
            for (int dy = 0; dy <= 1; ++dy) {
                for (int dx = 0; dx <= 1; ++dx) {
                    const TileKey key{level, 0, (fx + dx) % columns, std::min(fy + dy, rows - 1)};
                    const TileLookup lookup = scheduler.tryGet(top, key, level);
                    if (lookup.state == TileLookup::State::Ready &&
                        lookup.tile->at(0, 0, 0) != expected(key.x)) {
                        ++wrong;
                    }
                    wanted.push_back({&top, key, level});
                }
            }
        }
        switch (random() % 16) {
            case 0:
                (void)scheduler.invalidate(base.contentHash());
                break;
            case 1:
                (void)scheduler.invalidate(detail.contentHash());
                break;
            case 2:
                scheduler.cancel(top, wanted[random() % wanted.size()].key);
                break;
            case 3:
                scheduler.cancelAll();
                break;
            default:
                scheduler.setWanted(wanted);
                break;
        }
        ++frames;
        std::this_thread::sleep_for(std::chrono::microseconds(random() % 2000));
    }
    stop = true;
    reader.join();
    scheduler.waitIdle();
    EXPECT_EQ(wrong.load(), 0);
    EXPECT_EQ(failures.load(), 0);
    EXPECT_GT(checked.load(), 100);
    EXPECT_GT(frames, 1000);
    EXPECT_LE(scheduler.peakCachedBytes(), budget + workers * kTileBytes);
    EXPECT_LE(scheduler.totals().bytes, budget);
}

}  // namespace
}  // namespace sylva
