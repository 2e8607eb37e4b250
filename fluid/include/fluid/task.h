// fluid — 2D SPH liquid for games.
#pragma once

#include <cstdint>
#include <memory>

namespace fluid {

/// Work the step hands to the host's workers: process items [begin, end) as worker `worker`
/// (0 .. workerCount-1, each index used by one thread at a time). Every fluid task writes only
/// the items of its range, so any split gives the same result.
using TaskCallback = void(uint32_t begin, uint32_t end, uint32_t worker, void* taskContext);

/// The host's thread system, lent to a world (the shape of Box2D v3's task hooks).
/// Leave `enqueue` null to run everything serially on the stepping thread.
/// Thread rule: `enqueue` and `finish` are called from the stepping thread only, one task at a
/// time (enqueue, then finish, before the next enqueue).
struct TaskHook {
    /// Starts `callback` over [0, itemCount) in ranges of at least `minRange` items (unit: items);
    /// may run it inline. Returns a token for `finish`, or nullptr when the work is already done.
    void* (*enqueue)(TaskCallback* callback, uint32_t itemCount, uint32_t minRange,
                     void* taskContext, void* userContext) = nullptr;
    /// Blocks until the task behind `userTask` (from `enqueue`) has finished every range.
    void (*finish)(void* userTask, void* userContext) = nullptr;
    /// Number of distinct worker indices the callback may see (unit: count; 1 .. 256).
    uint32_t workerCount = 1;
    /// Passed back to `enqueue` and `finish` untouched.
    void* userContext = nullptr;
};

/// The cores this process may run on: its CPU affinity on Linux, else
/// `std::thread::hardware_concurrency()` (unit: count; >= 1). Any thread.
uint32_t usableCores();

/// A small fixed-size thread pool for hosts without their own: `threadCount()` threads, the
/// calling thread included, each with its share of every task; `workerCount` asks for them and
/// is capped at `usableCores()`: a thread more than the cores only waits for a time slice
/// (bench/scaling.md, More workers than cores). Results do not depend on the worker or thread count. Thread rule: `hook()` may be shared by
/// several worlds that step on the same thread; a pool must outlive the worlds using its hook.
class ThreadPool {
public:
    /// Starts `threadCount() - 1` threads for `workerCount` workers (unit: count; 1 .. 256;
    /// 1 means serial, no threads; more than `usableCores()` runs as many as the cores).
    explicit ThreadPool(uint32_t workerCount);
    /// Joins the threads. Must not be called while a task runs.
    ~ThreadPool();
    /// Not copyable: the threads belong to one pool.
    ThreadPool(const ThreadPool&) = delete;
    /// Not assignable.
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// The hook to put in `WorldDef::tasks`.
    TaskHook hook();
    /// Workers asked for, the calling thread included (unit: count; the hook's `workerCount`).
    uint32_t workerCount() const { return m_workerCount; }
    /// Threads that run the tasks, the calling thread included: `min(workerCount,
    /// usableCores())` (unit: count; >= 1). Callbacks see worker indices below it.
    uint32_t threadCount() const { return m_threadCount; }

private:
    struct Impl; // threads and the running task (thread_pool.cpp)
    uint32_t m_workerCount = 1;
    uint32_t m_threadCount = 1;
    std::unique_ptr<Impl> m_impl;
};

} // namespace fluid
