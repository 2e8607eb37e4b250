// fluid — the default thread pool.
//
// A task is claimed in ranges by whichever thread is running: the calling thread works too, and
// it waits only for the ranges other threads have claimed and not yet finished, never for a
// worker to wake up. So a worker that another process keeps off its core (a game's render or
// audio thread, the OS) costs at most the range it holds, not a scheduler time slice per
// hand-over. Every fluid task writes only its own items, so which thread runs which range does
// not change any result.
//
// A hand-over is bound by the cache lines that move between cores (about 0.1-0.2 us each), so
// each thread counts its part's finished items on the part's own line, and the mutex and
// condition variables are touched only when a thread really sleeps (a waiting flag read after
// the state it waits for changed; sequentially consistent on both sides, so one of them sees
// the other).
#include <fluid/error.h>
#include <fluid/task.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

namespace fluid {

namespace {

// A stage hands work to the pool a few hundred times per frame. Waking a sleeping thread takes
// tens of microseconds (a futex round trip; more in a virtual machine), which at 4,000 particles
// was as long as the work itself. So both sides first spin this long on the atomics, and only
// then sleep: between frames the workers go back to sleep within this time.
constexpr auto kSpin = std::chrono::microseconds(50);

inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Spins until done() or kSpin has passed; returns done().
template <class Done> bool spinUntil(Done&& done) {
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (uint32_t k = 0;; ++k) {
        if (done()) {
            return true;
        }
        cpuRelax();
        if ((k & 63) == 63 && std::chrono::steady_clock::now() >= until) {
            return done();
        }
    }
}

} // namespace

struct ThreadPool::Impl {
    // One thread's share of a task: a contiguous part of the items that its own thread works
    // from the front, and that a thread done with its own part takes ranges from too. On its
    // own cache line: the threads claim from different parts at the same time.
    struct alignas(64) Part {
        // The task's generation (high 32 bits) and the part's first unclaimed item (low 32).
        std::atomic<uint64_t> cursor{0};
        std::atomic<uint32_t> end{0};       // one past the part's last item
        std::atomic<uint32_t> remaining{0}; // items not finished yet
    };

    std::vector<std::thread> threads;
    std::vector<Part> parts; // one per thread, the caller's first
    std::mutex mutex;
    std::condition_variable wake; // a new task (or stop) for the workers
    std::condition_variable done; // the task's last range finished, for the caller
    // The running task. Its fields are atomics because a worker that woke for an earlier task
    // may still read them while the next one is set up; its claim then fails on the cursor's
    // generation, so it never runs a range of a task it did not see start. All accesses are
    // sequentially consistent: a claim that succeeds read the fields of its own task.
    std::atomic<TaskCallback*> callback{nullptr};
    std::atomic<void*> context{nullptr};
    std::atomic<uint32_t> rangeSize{1};
    std::atomic<uint32_t> generation{0}; // tasks started; workers wait for it to change
    std::atomic<bool> stop{false};
    // Sleepers: workers asleep on `wake` (or about to check before sleeping), and whether the
    // caller is asleep on `done`. Set under the mutex before the sleeper's last check.
    std::atomic<uint32_t> sleepers{0};
    std::atomic<bool> callerAsleep{false};

    explicit Impl(uint32_t workerCount) : parts(workerCount) {}

    // Claims the next range of `part` for task `gen`; false when the part is done (or the task
    // is not `gen` any more).
    bool claim(Part& part, uint32_t gen, uint32_t& begin, uint32_t& end) {
        uint64_t cur = part.cursor.load();
        while (uint32_t(cur >> 32) == gen) {
            begin = uint32_t(cur);
            const uint32_t last = part.end.load();
            if (begin >= last) {
                return false;
            }
            const uint32_t size = rangeSize.load();
            end = last - begin <= size ? last : begin + size;
            if (part.cursor.compare_exchange_weak(cur, (uint64_t(gen) << 32) | end)) {
                return true;
            }
        }
        return false;
    }

    // True when every part of the running task has finished all its items.
    bool finished() const {
        for (const Part& part : parts) {
            if (part.remaining.load() != 0) {
                return false;
            }
        }
        return true;
    }

    // Runs the ranges of `part` for task `gen` as `worker` until none is left. A worker (not
    // the caller) that finishes a part's last items wakes the caller if it sleeps.
    void drain(Part& part, uint32_t gen, uint32_t worker, bool notify) {
        uint32_t begin = 0, end = 0;
        while (claim(part, gen, begin, end)) {
            callback.load()(begin, end, worker, context.load());
            if (part.remaining.fetch_sub(end - begin) == end - begin && notify &&
                callerAsleep.load()) {
                // The caller checks `finished` under the mutex after setting its flag: taking
                // the mutex here means the notification cannot fall before its wait.
                std::lock_guard<std::mutex> lock(mutex);
                done.notify_one();
            }
        }
    }

    // Runs ranges of task `gen` on thread `thread` (also its worker index) until none is left:
    // its own part first, then the others' in turn. So each thread works the same items in
    // every task of the same size (the data its last task wrote is still in its cache), and a
    // thread another process keeps off its core costs at most the range it holds.
    void runRanges(uint32_t gen, uint32_t thread, bool notify) {
        const auto count = uint32_t(parts.size());
        for (uint32_t k = 0; k < count; ++k) {
            drain(parts[(thread + k) % count], gen, thread, notify);
        }
    }

    void threadMain(uint32_t thread) {
        uint32_t seen = 0;
        for (;;) {
            const auto woken = [&] {
                return stop.load() || generation.load() != seen;
            };
            if (!spinUntil(woken)) {
                std::unique_lock<std::mutex> lock(mutex);
                sleepers.fetch_add(1);
                wake.wait(lock, woken);
                sleepers.fetch_sub(1);
            }
            if (stop.load()) {
                return;
            }
            seen = generation.load();
            runRanges(seen, thread, true);
        }
    }
};

uint32_t usableCores() {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
    // A WebAssembly build without threads (docs/web.md): no thread can start, every task runs
    // on the stepping thread.
    return 1;
#elif defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) {
        return std::max(1u, uint32_t(CPU_COUNT(&set)));
    }
#endif
    return std::max(1u, std::thread::hardware_concurrency());
}

ThreadPool::ThreadPool(uint32_t workerCount) : m_workerCount(workerCount) {
    if (workerCount < 1 || workerCount > 256) {
        throw Error("ThreadPool: workerCount = " + std::to_string(workerCount) +
                        " is out of range [1, 256]",
                    ErrorCode::OutOfRange);
    }
    m_threadCount = std::min(workerCount, usableCores());
    m_impl = std::make_unique<Impl>(m_threadCount);
    m_impl->threads.reserve(m_threadCount - 1);
    for (uint32_t t = 1; t < m_threadCount; ++t) {
        m_impl->threads.emplace_back([impl = m_impl.get(), t] { impl->threadMain(t); });
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(m_impl->mutex);
        m_impl->stop.store(true);
    }
    m_impl->wake.notify_all();
    for (std::thread& thread : m_impl->threads) {
        thread.join();
    }
}

TaskHook ThreadPool::hook() {
    TaskHook hook;
    hook.enqueue = [](TaskCallback* callback, uint32_t itemCount, uint32_t minRange,
                      void* taskContext, void* userContext) -> void* {
        Impl& pool = *static_cast<Impl*>(userContext);
        if (pool.threads.empty()) {
            callback(0, itemCount, 0, taskContext);
            return nullptr;
        }
        const uint32_t gen = pool.generation.load() + 1;
        // Stragglers of the last task stop claiming before its fields change.
        for (Impl::Part& part : pool.parts) {
            part.cursor.store(uint64_t(gen) << 32);
        }
        pool.callback.store(callback);
        pool.context.store(taskContext);
        // Thread t's part: items [count t / T, count (t + 1) / T), in ranges of a quarter of a
        // part (at least minRange): small enough for the others to share a slow thread's part.
        const auto threads = uint32_t(pool.parts.size());
        for (uint32_t t = 0; t < threads; ++t) {
            const auto begin = uint32_t(uint64_t(itemCount) * t / threads);
            const auto end = uint32_t(uint64_t(itemCount) * (t + 1) / threads);
            pool.parts[t].end.store(end);
            pool.parts[t].remaining.store(end - begin);
            pool.parts[t].cursor.store((uint64_t(gen) << 32) | begin);
        }
        const uint32_t target = (itemCount + threads * 4 - 1) / (threads * 4);
        pool.rangeSize.store(std::max(std::max(minRange, target), 1u));
        pool.generation.store(gen);
        // A worker about to sleep counted itself before its last look at the generation.
        if (pool.sleepers.load() != 0) {
            { std::lock_guard<std::mutex> lock(pool.mutex); }
            pool.wake.notify_all();
        }
        return &pool;
    };
    hook.finish = [](void* userTask, void*) {
        if (userTask == nullptr) {
            return;
        }
        Impl& pool = *static_cast<Impl*>(userTask);
        // The caller works until no range is left, then waits for the ranges still running.
        pool.runRanges(pool.generation.load(), 0, false);
        const auto idle = [&pool] { return pool.finished(); };
        if (!spinUntil(idle)) {
            std::unique_lock<std::mutex> lock(pool.mutex);
            pool.callerAsleep.store(true);
            pool.done.wait(lock, idle);
            pool.callerAsleep.store(false);
        }
    };
    hook.workerCount = m_threadCount; // the worker indices callbacks see
    hook.userContext = m_impl.get();
    return hook;
}

} // namespace fluid
