// Scheduler: the concurrent TileProvider of seed 001 §4.6-4.7. The render thread
// posts tile requests (with a priority) to a manager thread, the manager keeps them in
// a priority queue, drops the ones no longer wanted and hands the most urgent one to
// each idle worker; workers produce tiles through the source graph and put them into
// one cache per source content hash. All caches share one memory budget and are
// pruned by distance to the focus (Fig. 4.3a); among tiles equally far, the one
// cheapest to get again per byte goes first, aged by GreedyDual-Size (Cao & Irani,
// "Cost-Aware WWW Proxy Caching Algorithms", USITS 1997): each tile's priority is the
// inflation value L at its last use plus its cost per byte (the seconds its source took
// to produce it, its inputs excluded, rounded down to a power of two so that costs
// within a factor of two tie and recency decides); the evicted tile's priority becomes
// L. So when one image's tiles exceed the budget, cheap tiles (a raster window read,
// a constant) are evicted before expensive ones (fractal noise, a filtered mask) that
// an edit or the next image would otherwise compute again; with equal costs it is LRU.
//
// What a frame uses goes last, what a task reads is pinned. A frame is the time from
// one wanted list (setWanted/cancelAll) to the next. Tiles used (read, produced) since
// the latest list are evicted only when no older tile is left, and then cheapest and
// least recently used first, not by distance: the distance rule assumes clipmap tiles
// around the focus, but a frame also reads tiles away from it (the ground under a city's
// buildings, at level 16, kilometres from the camera), which the rule made the first
// victims right after they were produced, so a building tile sampling them produced the
// same tiles again and again (issue 17: minutes a frame). A scheduler that never gets a
// wanted list (tools reading synchronously) has no frames: distance first, as above.
// Inputs a running task has read through tile() are not evicted until the task ends
// (the cache may exceed the budget by them meanwhile, and is pruned when they are
// released), so a source that reads an input again (GroundSampler keeps one tile) never
// makes the scheduler produce it twice within one task.
//
// Threads and OS priority: the manager runs one nice step below the creating thread,
// workers `workerNiceIncrement` steps below it (Linux: setpriority(PRIO_PROCESS, tid)
// on each thread's own id, which only lowers priority and needs no privilege), so the
// render thread keeps the CPU it needs while workers fill the caches.
//
// Dependencies: a worker (or any thread) calling tile() for an input finds it cached,
// waits if another thread is producing it, or takes the task over and produces it
// depth-first itself. The source graph is acyclic, so waits form no cycle and nothing
// deadlocks; a (source hash, key) is produced by at most one thread at a time, and a
// tile that is cached is never produced again (unless evicted or invalidated).
//
// Failures: a failed tile is reported once through the failure sink, counted, and
// remembered; later requests return the same error without retrying.
//
// Synchronisation: one mutex guards caches, queue and task table; it is held only for
// map operations, never while a source produces (tiles are immutable once shared).
// The seed uses one mutex per cache; with a handful of workers and millisecond tiles
// the single lock is uncontended and makes the global budget exact.
//
// Lifetime: every Source handed to the scheduler must outlive the tasks that refer to
// it. Before destroying a source graph call retainOnly() with the hashes still alive: it
// forgets every request and task not yet running and returns after the running ones
// finished (cancelAll() only cancels what is queued).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "sylva/core/sources/Source.h"
#include "sylva/core/tiles/DiskTileCache.h"

namespace sylva {

// One task a worker took from the queue and what it cost, inputs included (for traces:
// a task that produces many inputs itself holds its worker that long, and the queue
// does not move while every worker is inside one).
struct SchedulerTaskReport {
    int worker = 0;             // 0..workerCount()-1
    std::string source;         // the task's source name
    TileKey key;                // the task's tile
    double startSeconds = 0;    // steady clock, since the scheduler was created
    double seconds = 0;         // wall time so far (running) or in all (finished)
    bool fromDisk = false;      // the task's own tile came from the disk cache
    double waitSeconds = 0;     // waiting for inputs another thread was producing
    std::size_t produced = 0;   // inputs produced within the task (any depth)
    std::size_t diskReads = 0;  // inputs read from the disk cache within the task
    // Inputs produced within the task per source name (read from disk not counted); kept
    // only when SchedulerOptions::taskSink is set.
    std::map<std::string, std::size_t> producedPerSource;
};

struct SchedulerOptions {
    TileFormat format;
    int workers = 0;                        // 0: std::thread::hardware_concurrency()
    std::size_t budgetBytes = 1024u << 20;  // all cached tiles together
    int workerNiceIncrement = 5;            // 0 keeps workers at the caller's priority
    // Called once per failed tile (from a worker or the requesting thread, never under
    // the scheduler's lock).
    std::function<void(const Error&)> failureSink;
    // The persistent tile cache (none: memory only). A tile missing from memory is read
    // from it before producing and written to it after (on the producing thread, outside
    // the lock). Shared: several schedulers may use one.
    std::shared_ptr<DiskTileCache> diskCache;
    // Called on the worker after each task it took from the queue (not for inputs it
    // produced within it), outside the lock; waitIdle() waits for it. Tracing only; none
    // by default.
    std::function<void(const SchedulerTaskReport&)> taskSink;
};

// Per source content hash, or the total over all sources.
struct SchedulerStatistics {
    std::string name;           // the first source seen with this hash (empty for totals)
    std::uint64_t hash = 0;     // the sources' content hash (0 for totals)
    std::size_t hits = 0;       // requests answered from the cache
    std::size_t misses = 0;     // tiles produced
    std::size_t diskHits = 0;   // tiles read from the disk cache instead of produced
    std::size_t bytes = 0;      // bytes cached now
    std::size_t tiles = 0;      // tiles cached now
    std::size_t evictions = 0;  // tiles pruned for the budget
    std::size_t failures = 0;   // distinct failed tiles
    double produceSeconds = 0;  // produce() time excluding nested inputs and waits

    // Adds `other`'s counters, cached tiles and bytes (name and hash stay this one's).
    SchedulerStatistics& operator+=(const SchedulerStatistics& other);
};

class Scheduler final : public TileProvider {
public:
    explicit Scheduler(SchedulerOptions options = {});
    ~Scheduler() override;  // queued tasks are dropped, running ones finish
    Scheduler(const Scheduler&) = delete;
    Scheduler& operator=(const Scheduler&) = delete;

    // Priority for `level` (coarse first) of visible or prefetched tiles (visible first).
    static int priority(int level, bool visible) { return (visible ? 0 : 1000) + level; }

    // Blocking: the tile from the cache, from the thread producing it, or produced on
    // the calling thread now (depth-first through its inputs).
    Result<TilePointer> tile(const Source& source, const TileKey& key) override;
    const TileFormat& format() const override { return options_.format; }

    // Non-blocking: the ready tile, the remembered error, or Pending after queuing a
    // request with `priority` (an existing request takes the smaller priority).
    TileLookup tryGet(const Source& source, const TileKey& key, int priority) override;
    void request(const Source& source, const TileKey& key, int priority);
    // Drops the queued task for this tile; a running one finishes and is cached.
    void cancel(const Source& source, const TileKey& key);
    // The tiles wanted now: queues the missing ones and cancels every queued task of an
    // earlier wanted list that is not in this one (seed 001 Algorithm 3, "cancel previous
    // tile tasks; enqueue taskList"). Tasks queued by tryGet/request (the vegetation
    // stream's instance tiles) are another client's: they survive a wanted list as long
    // as they were asked for again since the previous one, and are cancelled at the
    // second list after their last request, so the terrain's list never starves them.
    void setWanted(const std::vector<TileRequest>& wanted) override;
    void cancelAll();

    // Pruning centre (radians): tiles far from it in their own level's grid go first.
    void setFocus(double latitude, double longitude) override;
    // Ring distance of `key` from the focus in tiles of the key's grid: 0 for the tile
    // under the focus and the quad around it, 1 for the ring adjacent to that quad...
    static int focusDistance(const TileKey& key, double latitude, double longitude);

    // Forgets tiles, failures and queued tasks of `contentHash` and of every hash that
    // (transitively) has it as an input; returns the hashes dropped.
    std::vector<std::uint64_t> invalidate(std::uint64_t contentHash);
    // Forgets everything of hashes not in `live` (after a project reload: changed nodes
    // and their dependents have new hashes, unchanged branches keep theirs and their
    // tiles), and every request and task not yet running, of any hash (they name the old
    // graph's Source objects; the new graph's ask again). Waits for every running task,
    // so the old graph may go.
    void retainOnly(const std::unordered_set<std::uint64_t>& live);

    // Blocks until no task is queued or running.
    void waitIdle();

    // Blocks until the manager has handled every request, cancellation and wanted list
    // posted so far (tasks may still be queued or running).
    void waitForMessages();
    // Blocks until something finished (a tile cached or failed) or `timeout` passed.
    void waitForProgress(std::chrono::milliseconds timeout) override;

    SchedulerStatistics totals() const;
    std::vector<SchedulerStatistics> statisticsPerSource() const;
    std::size_t budgetBytes() const;
    const std::shared_ptr<DiskTileCache>& diskCache() const { return options_.diskCache; }
    void setBudgetBytes(std::size_t bytes);
    std::size_t peakCachedBytes() const;
    std::size_t queuedTasks() const;
    // Tasks finished so far (a tile cached or failed, on any thread): a viewer redraws a
    // still view only when this changed, so its frames do not take the CPU the workers
    // need while nothing new can be shown.
    std::uint64_t finishedTasks() const;
    int workerCount() const { return static_cast<int>(workers_.size()); }
    // The task each busy worker is inside now (seconds so far, inputs produced so far).
    std::vector<SchedulerTaskReport> runningTasks() const;

private:
    struct TaskId {
        std::uint64_t hash = 0;
        TileKey key;
        friend bool operator==(const TaskId&, const TaskId&) = default;
        friend auto operator<=>(const TaskId&, const TaskId&) = default;
    };
    struct TaskIdHash {
        std::size_t operator()(const TaskId& id) const {
            return TileKeyHash{}(id.key) ^
                   static_cast<std::size_t>(id.hash * 0x9E3779B97F4A7C15ull);
        }
    };
    enum class TaskState { Queued, Dispatched, Running };
    struct Task {
        const Source* source = nullptr;
        int priority = 0;
        std::uint64_t sequence = 0;
        TaskState state = TaskState::Queued;
        std::uint64_t generation = 0;    // of the hash when the task started running
        bool requested = false;          // asked for by tryGet/request (not only a wanted list)
        std::uint64_t askedInRound = 0;  // lists posted before tryGet/request last asked
    };
    struct CachedTile {
        TilePointer tile;
        std::uint64_t lastUse = 0;
        double costPerMiB = 0;    // GreedyDual-Size: produce seconds per MiB, rounded
        double priority = 0;      // inflation at the last use + costPerMiB
        std::uint64_t round = 0;  // wanted lists posted before the last use (its frame)
    };
    // One cache per source content hash (seed 001 §4.4.3).
    struct SourceCache {
        std::unordered_map<TileKey, CachedTile, TileKeyHash> tiles;
        std::map<TileKey, Error> failures;
        SchedulerStatistics statistics;
        std::vector<std::uint64_t> inputs;  // content hashes of the source's inputs
        std::uint64_t generation = 0;       // bumped by invalidation
    };
    // The inputs a task running on this thread has read so far (pinned in pins_).
    struct PinScope {
        const Scheduler* owner = nullptr;
        std::vector<TaskId> inputs;
    };
    static thread_local PinScope* pinScope_;  // the innermost task on this thread, or null
    // The worker's task being run on this thread (guarded by mutex_), or null: on a
    // worker, inside its task; elsewhere (the render thread's tile()) always null.
    static thread_local SchedulerTaskReport* currentTask_;
    static thread_local int taskDepth_;  // run() calls active on this thread
    struct Message {
        enum class Kind { Request, Cancel, SetWanted, CancelAll } kind;
        std::vector<TileRequest> requests;  // Request (one), SetWanted (all)
    };

    void managerLoop();
    void workerLoop(int worker);
    // Runs a task whose state the caller set to Running; the lock is released while the
    // source produces. Returns the tile or the error.
    Result<TilePointer> run(std::unique_lock<std::mutex>& lock, const TaskId& id,
                            const Source& source);
    SourceCache& cacheFor(const Source& source);  // registers the source's hash and inputs
    void queueLocked(const Source& source, const TileKey& key, int priority, bool wanted);
    void removeQueuedLocked(const TaskId& id);
    // `seconds`: what producing (or reading) the tile cost, its inputs excluded.
    void insertLocked(const TaskId& id, TilePointer tile, double seconds);
    void touchLocked(CachedTile& cached);  // a use: recency and GreedyDual-Size priority
    void pruneLocked();
    // Releases the pins a finished task took on its inputs; prunes if over budget.
    void unpinLocked(const std::vector<TaskId>& inputs);
    void dropHashLocked(std::uint64_t hash);
    // Drops unhandled requests (wanted lists stay, emptied) and every task not running.
    void forgetUnstartedLocked();
    void postLocked(Message message);

    SchedulerOptions options_;
    mutable std::mutex mutex_;
    std::condition_variable managerWake_;  // messages arrived, a worker became idle, stop
    std::condition_variable workerWake_;   // a task was dispatched, stop
    std::condition_variable progress_;     // a task finished
    std::size_t reportsInFlight_ = 0;      // failure and task sink calls running (unlocked)
    std::deque<Message> inbox_;            // render thread → manager
    std::deque<TaskId> dispatched_;        // manager → workers
    std::set<std::tuple<int, std::uint64_t, TaskId>> queue_;  // (priority, sequence, id)
    std::unordered_map<TaskId, Task, TaskIdHash> tasks_;
    std::unordered_map<std::uint64_t, SourceCache> caches_;
    // Tiles pinned as inputs of running tasks: the number of tasks holding each.
    std::unordered_map<TaskId, int, TaskIdHash> pins_;
    std::uint64_t sequence_ = 0;
    std::uint64_t wantedRound_ = 0;   // setWanted/cancelAll lists processed by the manager
    std::uint64_t postedRounds_ = 0;  // setWanted/cancelAll lists posted (≥ wantedRound_)
    std::uint64_t finished_ = 0;      // tasks finished (finishedTasks())
    std::uint64_t useClock_ = 0;
    double inflation_ = 0;  // GreedyDual-Size L: the priority of the last tile evicted
    std::size_t cachedBytes_ = 0;
    std::size_t peakBytes_ = 0;
    std::optional<std::pair<double, double>> focus_;  // latitude, longitude
    int idleWorkers_ = 0;
    bool stopping_ = false;
    std::thread manager_;
    std::vector<std::thread> workers_;
    // Per worker: its task while it runs one (workerBusy_), for runningTasks().
    std::vector<SchedulerTaskReport> workerTasks_;
    std::vector<char> workerBusy_;
    std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
};

}  // namespace sylva
