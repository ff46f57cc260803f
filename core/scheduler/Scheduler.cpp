#include "sylva/core/scheduler/Scheduler.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <numbers>
#include <tuple>

#include "sylva/core/base/WorkerPool.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace sylva {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds spent in nested produce() calls and in waits for inputs on this thread, so
// each source's produce time excludes its inputs (seed 001 §4.6: depth-first).
thread_local double nestedSeconds = 0.0;

// Lowers the calling thread's OS priority by `increment` nice steps (Linux: nice is
// per thread; setpriority on the thread id affects only this thread).
void lowerThreadPriority(int increment) {
#if defined(__linux__)
    if (increment <= 0) {
        return;
    }
    const id_t thread = static_cast<id_t>(gettid());
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, thread);
    if (errno == 0) {
        (void)setpriority(PRIO_PROCESS, thread, std::min(19, current + increment));
    }
#else
    (void)increment;
#endif
}

}  // namespace

thread_local Scheduler::PinScope* Scheduler::pinScope_ = nullptr;
thread_local SchedulerTaskReport* Scheduler::currentTask_ = nullptr;
thread_local int Scheduler::taskDepth_ = 0;

Scheduler::Scheduler(SchedulerOptions options) : options_(std::move(options)) {
    int workers = options_.workers;
    if (workers <= 0) {
        workers = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    }
    manager_ = std::thread([this] {
        lowerThreadPriority(options_.workerNiceIncrement > 0 ? 1 : 0);
        managerLoop();
    });
    workerTasks_.resize(static_cast<std::size_t>(workers));
    workerBusy_.assign(static_cast<std::size_t>(workers), 0);
    for (int i = 0; i < workers; ++i) {
        workers_.emplace_back([this, i] {
            lowerThreadPriority(options_.workerNiceIncrement);
            WorkerPool::runSeriallyOnThisThread();
            workerLoop(i);
        });
    }
}

Scheduler::~Scheduler() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    managerWake_.notify_all();
    workerWake_.notify_all();
    manager_.join();
    for (std::thread& worker : workers_) {
        worker.join();
    }
}

int Scheduler::focusDistance(const TileKey& key, double latitude, double longitude) {
    const double columns = key.columns();
    const double rows = key.rows();
    const double fx = (longitude + std::numbers::pi) / (2 * std::numbers::pi) * columns;
    const double fy = (std::numbers::pi / 2 - latitude) / std::numbers::pi * rows;
    // A clipmap window is one tile wide around the focus, so it touches the quad of
    // tiles [floor(f - 1/2), floor(f + 1/2)] in each direction (Fig. 4.3b).
    const auto x0 = static_cast<std::int64_t>(std::floor(fx - 0.5));
    const auto x1 = static_cast<std::int64_t>(std::floor(fx + 0.5));
    const auto y0 = static_cast<std::int64_t>(std::floor(fy - 0.5));
    const auto y1 = static_cast<std::int64_t>(std::floor(fy + 0.5));
    const auto span = [](std::int64_t v, std::int64_t lo, std::int64_t hi) -> std::int64_t {
        return v < lo ? lo - v : (v > hi ? v - hi : 0);
    };
    const auto n = static_cast<std::int64_t>(columns);
    std::int64_t dx = span(key.x, x0, x1);
    // Columns wrap around the globe: the shorter way counts.
    dx = std::min({dx, span(key.x + n, x0, x1), span(key.x - n, x0, x1)});
    const std::int64_t dy = span(key.y, y0, y1);
    return static_cast<int>(std::min<std::int64_t>(std::max(dx, dy), 1 << 30));
}

Scheduler::SourceCache& Scheduler::cacheFor(const Source& source) {
    const std::uint64_t hash = source.contentHash();
    if (auto it = caches_.find(hash); it != caches_.end()) {
        return it->second;
    }
    std::vector<std::uint64_t> inputs;
    for (const Source* input : source.inputs()) {
        if (input != nullptr) {
            cacheFor(*input);
            inputs.push_back(input->contentHash());
        }
    }
    SourceCache& cache = caches_[hash];  // inserted after the inputs: no rehash below
    cache.statistics.name = source.name();
    cache.inputs = std::move(inputs);
    cache.generation = ++sequence_;
    return cache;
}

Result<TilePointer> Scheduler::tile(const Source& source, const TileKey& key) {
    SYLVA_CHECK_MESSAGE(key.valid(), "Scheduler::tile: invalid tile key");
    const TaskId id{source.contentHash(), key};
    std::unique_lock lock(mutex_);
    // An input of a task running on this thread: pinned until that task ends (before it
    // is produced, so inserting it never evicts it).
    if (pinScope_ != nullptr && pinScope_->owner == this) {
        pinScope_->inputs.push_back(id);
        ++pins_[id];
    }
    while (true) {
        SourceCache& cache = cacheFor(source);
        if (auto hit = cache.tiles.find(key); hit != cache.tiles.end()) {
            ++cache.statistics.hits;
            touchLocked(hit->second);
            return hit->second.tile;
        }
        if (auto failed = cache.failures.find(key); failed != cache.failures.end()) {
            return failed->second;
        }
        auto task = tasks_.find(id);
        if (task != tasks_.end() && task->second.state == TaskState::Running) {
            // Another thread produces it: wait (the graph is acyclic, so that thread
            // never waits for us).
            const auto start = Clock::now();
            progress_.wait(lock, [&] {
                auto it = tasks_.find(id);
                return it == tasks_.end() || it->second.state != TaskState::Running;
            });
            const double waited = std::chrono::duration<double>(Clock::now() - start).count();
            nestedSeconds += waited;
            if (currentTask_ != nullptr) {
                currentTask_->waitSeconds += waited;
            }
            continue;  // cached, failed, or evicted/invalidated meanwhile: look again
        }
        if (task != tasks_.end()) {
            removeQueuedLocked(id);  // take the queued task over; a worker skips it
        } else {
            task = tasks_.emplace(id, Task{&source, 0, ++sequence_, TaskState::Running, 0}).first;
        }
        task->second.state = TaskState::Running;
        task->second.source = &source;
        return run(lock, id, source);
    }
}

Result<TilePointer> Scheduler::run(std::unique_lock<std::mutex>& lock, const TaskId& id,
                                   const Source& source) {
    const std::uint64_t generation = cacheFor(source).generation;
    tasks_.at(id).generation = generation;
    lock.unlock();

    const double outerNested = nestedSeconds;
    nestedSeconds = 0.0;
    ++taskDepth_;
    PinScope scope{this, {}};
    PinScope* const outerScope = pinScope_;
    pinScope_ = &scope;
    const auto start = Clock::now();
    DiskTileCache* disk = options_.diskCache.get();
    TilePointer stored = disk != nullptr ? disk->load(id.hash, id.key, options_.format) : nullptr;
    const bool fromDisk = stored != nullptr;
    Result<TilePointer> produced =
        fromDisk ? Result<TilePointer>(std::move(stored)) : source.produce(id.key, *this);
    if (disk != nullptr && !fromDisk && produced) {
        disk->store(id.hash, options_.format, *produced.value());
    }
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const double own = std::max(0.0, elapsed - nestedSeconds);
    nestedSeconds = outerNested + elapsed;
    pinScope_ = outerScope;
    if (produced) {
        SYLVA_CHECK(produced.value() != nullptr);
        SYLVA_CHECK(produced.value()->key() == id.key);
    } else {
        produced = Error{"source '" + source.name() + "', tile " + id.key.toString() + ": " +
                         produced.error().message};
    }

    lock.lock();
    --taskDepth_;
    if (currentTask_ != nullptr) {
        if (taskDepth_ == 0) {
            currentTask_->fromDisk = fromDisk;
        } else if (fromDisk) {
            ++currentTask_->diskReads;
        } else {
            ++currentTask_->produced;
            if (options_.taskSink) {
                // A string-keyed count per nested production: only when someone reads it.
                ++currentTask_->producedPerSource[source.name()];
            }
        }
    }
    tasks_.erase(id);
    ++finished_;
    unpinLocked(scope.inputs);
    bool report = false;
    auto cache = caches_.find(id.hash);
    // A task of an invalidated (or dropped) hash may have read stale inputs: discard.
    if (cache != caches_.end() && cache->second.generation == generation) {
        ++(fromDisk ? cache->second.statistics.diskHits : cache->second.statistics.misses);
        cache->second.statistics.produceSeconds += own;
        if (produced) {
            insertLocked(id, produced.value(), own);
        } else if (cache->second.failures.emplace(id.key, produced.error()).second) {
            ++cache->second.statistics.failures;
            report = true;
        }
    }
    if (report && options_.failureSink) {
        // Counted until the sink returns, so waitIdle() also waits for the report.
        ++reportsInFlight_;
        lock.unlock();
        options_.failureSink(produced.error());
        lock.lock();
        --reportsInFlight_;
    }
    progress_.notify_all();
    return produced;
}

void Scheduler::touchLocked(CachedTile& cached) {
    cached.lastUse = ++useClock_;
    cached.priority = inflation_ + cached.costPerMiB;
    cached.round = postedRounds_;
}

void Scheduler::unpinLocked(const std::vector<TaskId>& inputs) {
    for (const TaskId& input : inputs) {
        auto pin = pins_.find(input);
        SYLVA_CHECK(pin != pins_.end() && pin->second > 0);
        if (--pin->second == 0) {
            pins_.erase(pin);
        }
    }
    if (!inputs.empty() && cachedBytes_ > options_.budgetBytes) {
        pruneLocked();
    }
}

void Scheduler::insertLocked(const TaskId& id, TilePointer tile, double seconds) {
    SourceCache& cache = caches_.at(id.hash);
    const std::size_t bytes = tile->bytes();
    auto [it, inserted] = cache.tiles.try_emplace(id.key);
    if (!inserted) {
        cache.statistics.bytes -= it->second.tile->bytes();
        cachedBytes_ -= it->second.tile->bytes();
        --cache.statistics.tiles;
    }
    // At least 0.1 ms a tile (a clock's resolution and the allocation), per MiB, rounded
    // down to a power of two: timing noise between equal tiles does not order them.
    constexpr double kMinimumSeconds = 1.0e-4;
    const double perMiB = std::max(seconds, kMinimumSeconds) /
                          (static_cast<double>(std::max<std::size_t>(bytes, 1)) / (1 << 20));
    it->second = CachedTile{std::move(tile), 0, std::exp2(std::floor(std::log2(perMiB))), 0};
    touchLocked(it->second);
    cache.statistics.bytes += bytes;
    ++cache.statistics.tiles;
    cachedBytes_ += bytes;
    if (cachedBytes_ > options_.budgetBytes) {
        pruneLocked();
    }
    peakBytes_ = std::max(peakBytes_, cachedBytes_);
}

void Scheduler::pruneLocked() {
    // Seed 001 Fig. 4.3a: keep the tiles of the current quad and the ring adjacent to
    // it; evict the farthest first. Among equally far ones the seed takes the least
    // recently used; here the cheapest to get again (GreedyDual-Size, see the header).
    // Tiles of the current frame come after all others and go cheapest, then least
    // recently used, first; pinned inputs of running tasks stay.
    struct Candidate {
        bool current;  // used since the latest wanted list
        int distance;
        double priority;
        std::uint64_t lastUse;
        std::uint64_t hash;
        TileKey key;
    };
    std::vector<Candidate> candidates;
    for (const auto& [hash, cache] : caches_) {
        for (const auto& [key, cached] : cache.tiles) {
            if (!pins_.empty() && pins_.count({hash, key}) != 0) {
                continue;
            }
            const bool current = postedRounds_ > 0 && cached.round == postedRounds_;
            const int distance =
                focus_ && !current ? focusDistance(key, focus_->first, focus_->second) : 0;
            candidates.push_back({current, distance, cached.priority, cached.lastUse, hash, key});
        }
    }
    // Earlier frames' tiles first, farthest first; then the lowest GreedyDual-Size
    // priority, then the least recently used.
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        if (a.current != b.current) {
            return b.current;
        }
        if (a.distance != b.distance) {
            return a.distance > b.distance;
        }
        return a.priority != b.priority ? a.priority < b.priority : a.lastUse < b.lastUse;
    });
    for (const Candidate& victim : candidates) {
        if (cachedBytes_ <= options_.budgetBytes) {
            break;
        }
        SourceCache& cache = caches_.at(victim.hash);
        auto it = cache.tiles.find(victim.key);
        if (victim.distance <= 1) {
            // Aging as GreedyDual-Size has it, but only by tiles evicted for their
            // priority: one evicted for its distance (Fig. 4.3a) says nothing of costs.
            inflation_ = std::max(inflation_, it->second.priority);
        }
        const std::size_t bytes = it->second.tile->bytes();
        cache.tiles.erase(it);
        cache.statistics.bytes -= bytes;
        --cache.statistics.tiles;
        ++cache.statistics.evictions;
        cachedBytes_ -= bytes;
    }
}

TileLookup Scheduler::tryGet(const Source& source, const TileKey& key, int priority) {
    SYLVA_CHECK_MESSAGE(key.valid(), "Scheduler::tryGet: invalid tile key");
    std::lock_guard lock(mutex_);
    SourceCache& cache = cacheFor(source);
    if (auto hit = cache.tiles.find(key); hit != cache.tiles.end()) {
        ++cache.statistics.hits;
        touchLocked(hit->second);
        return {TileLookup::State::Ready, hit->second.tile, {}};
    }
    if (auto failed = cache.failures.find(key); failed != cache.failures.end()) {
        return {TileLookup::State::Failed, nullptr, failed->second};
    }
    auto task = tasks_.find({source.contentHash(), key});
    if (task != tasks_.end()) {
        // Asked again: the task survives the next list. Recorded here, not by a message,
        // because no message is posted for a task the manager already holds; counted in
        // lists posted so far, since lists still in the inbox come before this ask.
        task->second.requested = true;
        task->second.askedInRound = std::max(task->second.askedInRound, postedRounds_);
    }
    if (task == tasks_.end() ||
        (task->second.state == TaskState::Queued && priority < task->second.priority)) {
        postLocked({Message::Kind::Request, {TileRequest{&source, key, priority}}});
    }
    return {};
}

void Scheduler::request(const Source& source, const TileKey& key, int priority) {
    SYLVA_CHECK_MESSAGE(key.valid(), "Scheduler::request: invalid tile key");
    std::lock_guard lock(mutex_);
    cacheFor(source);
    postLocked({Message::Kind::Request, {TileRequest{&source, key, priority}}});
}

void Scheduler::cancel(const Source& source, const TileKey& key) {
    std::lock_guard lock(mutex_);
    postLocked({Message::Kind::Cancel, {TileRequest{&source, key, 0}}});
}

void Scheduler::setWanted(const std::vector<TileRequest>& wanted) {
    std::lock_guard lock(mutex_);
    for (const TileRequest& request : wanted) {
        SYLVA_CHECK(request.source != nullptr && request.key.valid());
        cacheFor(*request.source);
    }
    ++postedRounds_;
    postLocked({Message::Kind::SetWanted, wanted});
}

void Scheduler::cancelAll() {
    std::lock_guard lock(mutex_);
    ++postedRounds_;
    postLocked({Message::Kind::CancelAll, {}});
}

void Scheduler::postLocked(Message message) {
    inbox_.push_back(std::move(message));
    managerWake_.notify_one();
}

void Scheduler::setFocus(double latitude, double longitude) {
    std::lock_guard lock(mutex_);
    focus_ = std::make_pair(latitude, longitude);
}

void Scheduler::queueLocked(const Source& source, const TileKey& key, int priority, bool wanted) {
    const TaskId id{source.contentHash(), key};
    SourceCache& cache = cacheFor(source);
    if (cache.tiles.count(key) != 0 || cache.failures.count(key) != 0) {
        return;
    }
    auto task = tasks_.find(id);
    if (task == tasks_.end()) {
        const std::uint64_t sequence = ++sequence_;
        tasks_.emplace(
            id, Task{&source, priority, sequence, TaskState::Queued, 0, !wanted, wantedRound_});
        queue_.emplace(priority, sequence, id);
        return;
    }
    if (!wanted) {
        task->second.requested = true;
        task->second.askedInRound = std::max(task->second.askedInRound, wantedRound_);
    }
    if (task->second.state == TaskState::Queued && priority < task->second.priority) {
        queue_.erase({task->second.priority, task->second.sequence, id});
        task->second.priority = priority;
        queue_.emplace(priority, task->second.sequence, id);
    }
}

void Scheduler::removeQueuedLocked(const TaskId& id) {
    auto task = tasks_.find(id);
    if (task != tasks_.end() && task->second.state == TaskState::Queued) {
        queue_.erase({task->second.priority, task->second.sequence, id});
    }
}

void Scheduler::managerLoop() {
    std::unique_lock lock(mutex_);
    while (true) {
        managerWake_.wait(lock, [&] {
            return stopping_ || !inbox_.empty() ||
                   (static_cast<std::size_t>(idleWorkers_) > dispatched_.size() && !queue_.empty());
        });
        if (stopping_) {
            return;
        }
        while (!inbox_.empty()) {
            Message message = std::move(inbox_.front());
            inbox_.pop_front();
            const auto cancelQueued = [&](const TaskId& id) {
                auto task = tasks_.find(id);
                if (task != tasks_.end() && task->second.state != TaskState::Running) {
                    removeQueuedLocked(id);
                    tasks_.erase(task);  // a dispatched one is skipped by its worker
                }
            };
            switch (message.kind) {
                case Message::Kind::Request:
                    queueLocked(*message.requests[0].source, message.requests[0].key,
                                message.requests[0].priority, false);
                    break;
                case Message::Kind::Cancel:
                    cancelQueued(
                        {message.requests[0].source->contentHash(), message.requests[0].key});
                    break;
                case Message::Kind::SetWanted:
                case Message::Kind::CancelAll: {
                    const bool all = message.kind == Message::Kind::CancelAll;
                    ++wantedRound_;
                    std::unordered_set<TaskId, TaskIdHash> wanted;
                    for (const TileRequest& request : message.requests) {
                        wanted.insert({request.source->contentHash(), request.key});
                    }
                    std::vector<TaskId> stale;
                    for (const auto& [id, task] : tasks_) {
                        // Another client's request lives until a list passes without it
                        // being asked for again.
                        const bool expired =
                            all || !task.requested || task.askedInRound + 1 < wantedRound_;
                        if (task.state != TaskState::Running && wanted.count(id) == 0 && expired) {
                            stale.push_back(id);
                        }
                    }
                    for (const TaskId& id : stale) {
                        cancelQueued(id);
                    }
                    for (const TileRequest& request : message.requests) {
                        queueLocked(*request.source, request.key, request.priority, true);
                    }
                    break;
                }
            }
        }
        // Hand the most urgent tasks to idle workers, one each, so later requests and
        // cancellations still reorder everything not yet started.
        while (static_cast<std::size_t>(idleWorkers_) > dispatched_.size() && !queue_.empty()) {
            const TaskId id = std::get<2>(*queue_.begin());
            queue_.erase(queue_.begin());
            tasks_.at(id).state = TaskState::Dispatched;
            dispatched_.push_back(id);
            workerWake_.notify_one();
        }
        progress_.notify_all();  // waitIdle() may be waiting for the inbox to drain
    }
}

void Scheduler::workerLoop(int worker) {
    std::unique_lock lock(mutex_);
    ++idleWorkers_;
    managerWake_.notify_one();
    while (true) {
        workerWake_.wait(lock, [&] { return stopping_ || !dispatched_.empty(); });
        if (stopping_) {
            return;
        }
        const TaskId id = dispatched_.front();
        dispatched_.pop_front();
        auto task = tasks_.find(id);
        if (task == tasks_.end() || task->second.state != TaskState::Dispatched) {
            managerWake_.notify_one();  // cancelled or taken over: the slot is free again
            continue;
        }
        task->second.state = TaskState::Running;
        const Source* source = task->second.source;
        --idleWorkers_;
        SchedulerTaskReport& report = workerTasks_[static_cast<std::size_t>(worker)];
        report = SchedulerTaskReport{};
        report.worker = worker;
        report.source = source->name();
        report.key = id.key;
        const auto start = Clock::now();
        report.startSeconds = std::chrono::duration<double>(start - created_).count();
        workerBusy_[static_cast<std::size_t>(worker)] = 1;
        currentTask_ = &report;
        (void)run(lock, id, *source);
        currentTask_ = nullptr;
        workerBusy_[static_cast<std::size_t>(worker)] = 0;
        report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        if (options_.taskSink) {
            // Counted like a failure report, so waitIdle() also waits for this one (the
            // lock was held since run() erased the task).
            const SchedulerTaskReport finished = report;
            ++reportsInFlight_;
            lock.unlock();
            options_.taskSink(finished);
            lock.lock();
            --reportsInFlight_;
            progress_.notify_all();
        }
        ++idleWorkers_;
        managerWake_.notify_one();
    }
}

std::vector<std::uint64_t> Scheduler::invalidate(std::uint64_t contentHash) {
    std::lock_guard lock(mutex_);
    // The hash and everything downstream of it (hashes include input hashes, so the
    // dependents' tiles were made from the stale ones).
    std::vector<std::uint64_t> dropped{contentHash};
    for (bool grew = true; grew;) {
        grew = false;
        for (const auto& [hash, cache] : caches_) {
            if (std::find(dropped.begin(), dropped.end(), hash) != dropped.end()) {
                continue;
            }
            for (std::uint64_t input : cache.inputs) {
                if (std::find(dropped.begin(), dropped.end(), input) != dropped.end()) {
                    dropped.push_back(hash);
                    grew = true;
                    break;
                }
            }
        }
    }
    for (std::uint64_t hash : dropped) {
        dropHashLocked(hash);
        if (auto cache = caches_.find(hash); cache != caches_.end()) {
            cache->second.generation = ++sequence_;  // running tasks of it are discarded
        }
    }
    return dropped;
}

void Scheduler::dropHashLocked(std::uint64_t hash) {
    auto cache = caches_.find(hash);
    if (cache != caches_.end()) {
        for (const auto& [key, cached] : cache->second.tiles) {
            cachedBytes_ -= cached.tile->bytes();
        }
        cache->second.tiles.clear();
        cache->second.failures.clear();
        cache->second.statistics.bytes = 0;
        cache->second.statistics.tiles = 0;
    }
    std::vector<TaskId> queued;
    for (const auto& [id, task] : tasks_) {
        if (id.hash == hash && task.state != TaskState::Running) {
            queued.push_back(id);
        }
    }
    for (const TaskId& id : queued) {
        removeQueuedLocked(id);
        tasks_.erase(id);
    }
}

void Scheduler::retainOnly(const std::unordered_set<std::uint64_t>& live) {
    std::unique_lock lock(mutex_);
    // A reload builds new Source objects for every node, unchanged ones (same hash) too:
    // every request not yet handled and every task not yet running names an object about
    // to be destroyed, whatever its hash (a worker dereferenced one: issue 20's village
    // walker test crashed in workerLoop after a reload). Forget them all, the next frame
    // asks the new objects; then wait for every running task, whose nested productions
    // and requests use the old objects too, and forget what they queued meanwhile.
    forgetUnstartedLocked();
    std::vector<std::uint64_t> dead;
    for (const auto& [hash, cache] : caches_) {
        if (live.count(hash) == 0) {
            dead.push_back(hash);
        }
    }
    for (std::uint64_t hash : dead) {
        dropHashLocked(hash);
    }
    progress_.wait(lock, [&] {
        return std::none_of(tasks_.begin(), tasks_.end(), [](const auto& entry) {
            return entry.second.state == TaskState::Running;
        });
    });
    forgetUnstartedLocked();
    for (std::uint64_t hash : dead) {
        cachedBytes_ -= caches_.at(hash).statistics.bytes;  // tiles a finishing task added
        caches_.erase(hash);
    }
}

void Scheduler::forgetUnstartedLocked() {
    // Wanted lists stay, emptied, so the manager still counts their rounds.
    std::erase_if(inbox_, [](const Message& message) {
        return message.kind == Message::Kind::Request || message.kind == Message::Kind::Cancel;
    });
    for (Message& message : inbox_) {
        message.requests.clear();
    }
    for (auto task = tasks_.begin(); task != tasks_.end();) {
        if (task->second.state == TaskState::Running) {
            ++task;
            continue;
        }
        removeQueuedLocked(task->first);
        task = tasks_.erase(task);  // a dispatched one is skipped by its worker
    }
}

void Scheduler::waitIdle() {
    std::unique_lock lock(mutex_);
    progress_.wait(lock, [&] { return inbox_.empty() && tasks_.empty() && reportsInFlight_ == 0; });
}

void Scheduler::waitForMessages() {
    std::unique_lock lock(mutex_);
    // The manager pops and handles messages under the lock: an empty inbox means handled.
    progress_.wait(lock, [&] { return inbox_.empty(); });
}

void Scheduler::waitForProgress(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    progress_.wait_for(lock, timeout);
}

SchedulerStatistics& SchedulerStatistics::operator+=(const SchedulerStatistics& other) {
    hits += other.hits;
    misses += other.misses;
    diskHits += other.diskHits;
    bytes += other.bytes;
    tiles += other.tiles;
    evictions += other.evictions;
    failures += other.failures;
    produceSeconds += other.produceSeconds;
    return *this;
}

SchedulerStatistics Scheduler::totals() const {
    std::lock_guard lock(mutex_);
    SchedulerStatistics total;
    for (const auto& [hash, cache] : caches_) {
        total += cache.statistics;
    }
    return total;
}

std::vector<SchedulerStatistics> Scheduler::statisticsPerSource() const {
    std::lock_guard lock(mutex_);
    std::vector<SchedulerStatistics> result;
    for (const auto& [hash, cache] : caches_) {
        result.push_back(cache.statistics);
        result.back().hash = hash;
    }
    std::sort(
        result.begin(), result.end(),
        [](const SchedulerStatistics& a, const SchedulerStatistics& b) { return a.name < b.name; });
    return result;
}

void Scheduler::setBudgetBytes(std::size_t bytes) {
    std::lock_guard lock(mutex_);
    options_.budgetBytes = bytes;
    if (cachedBytes_ > bytes) {
        pruneLocked();
    }
}

std::size_t Scheduler::budgetBytes() const {
    std::lock_guard lock(mutex_);
    return options_.budgetBytes;
}

std::size_t Scheduler::peakCachedBytes() const {
    std::lock_guard lock(mutex_);
    return peakBytes_;
}

std::uint64_t Scheduler::finishedTasks() const {
    std::lock_guard lock(mutex_);
    return finished_;
}

std::vector<SchedulerTaskReport> Scheduler::runningTasks() const {
    std::lock_guard lock(mutex_);
    const double now = std::chrono::duration<double>(Clock::now() - created_).count();
    std::vector<SchedulerTaskReport> running;
    for (std::size_t i = 0; i < workerTasks_.size(); ++i) {
        if (workerBusy_[i] != 0) {
            running.push_back(workerTasks_[i]);
            running.back().seconds = now - running.back().startSeconds;
        }
    }
    return running;
}

std::size_t Scheduler::queuedTasks() const {
    std::lock_guard lock(mutex_);
    return queue_.size();
}

}  // namespace sylva
