// fluid — the default thread pool.
#include <fluid/error.h>
#include <fluid/task.h>

#include <algorithm>
#include <chrono>
#include <string>

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

ThreadPool::ThreadPool(uint32_t workerCount) : m_workerCount(workerCount) {
    if (workerCount < 1 || workerCount > 256) {
        throw Error("ThreadPool: workerCount = " + std::to_string(workerCount) +
                    " is out of range [1, 256]");
    }
    m_threads.reserve(workerCount - 1);
    for (uint32_t w = 1; w < workerCount; ++w) {
        m_threads.emplace_back([this, w] { workerMain(w); });
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop.store(true);
    }
    m_wake.notify_all();
    for (std::thread& thread : m_threads) {
        thread.join();
    }
}

TaskHook ThreadPool::hook() {
    TaskHook hook;
    hook.enqueue = &ThreadPool::enqueueTask;
    hook.finish = &ThreadPool::finishTask;
    hook.workerCount = m_workerCount;
    hook.userContext = this;
    return hook;
}

void* ThreadPool::enqueueTask(TaskCallback* callback, uint32_t itemCount, uint32_t minRange,
                              void* taskContext, void* userContext) {
    auto* pool = static_cast<ThreadPool*>(userContext);
    if (pool->m_threads.empty()) {
        callback(0, itemCount, 0, taskContext);
        return nullptr;
    }
    {
        std::lock_guard<std::mutex> lock(pool->m_mutex);
        pool->m_callback = callback;
        pool->m_context = taskContext;
        pool->m_itemCount = itemCount;
        // About four ranges per worker balances load without much claiming overhead.
        const uint32_t target =
            (itemCount + pool->m_workerCount * 4 - 1) / (pool->m_workerCount * 4);
        pool->m_rangeSize = std::max(std::max(minRange, target), 1u);
        pool->m_nextBegin.store(0, std::memory_order_relaxed);
        pool->m_busy.store(static_cast<uint32_t>(pool->m_threads.size()),
                           std::memory_order_relaxed);
        pool->m_generation.fetch_add(1, std::memory_order_release);
    }
    pool->m_wake.notify_all();
    return pool;
}

void ThreadPool::finishTask(void* userTask, void* userContext) {
    auto* pool = static_cast<ThreadPool*>(userContext);
    if (userTask == nullptr) {
        return;
    }
    pool->runRanges(0);
    const auto idle = [pool] { return pool->m_busy.load(std::memory_order_acquire) == 0; };
    if (!spinUntil(idle)) {
        std::unique_lock<std::mutex> lock(pool->m_mutex);
        pool->m_done.wait(lock, idle);
    }
    std::lock_guard<std::mutex> lock(pool->m_mutex);
    pool->m_callback = nullptr;
}

void ThreadPool::runRanges(uint32_t worker) {
    for (;;) {
        const uint32_t begin = m_nextBegin.fetch_add(m_rangeSize, std::memory_order_relaxed);
        if (begin >= m_itemCount) {
            return;
        }
        m_callback(begin, std::min(m_itemCount, begin + m_rangeSize), worker, m_context);
    }
}

void ThreadPool::workerMain(uint32_t worker) {
    uint64_t seen = 0;
    for (;;) {
        const auto woken = [&] {
            return m_stop.load(std::memory_order_relaxed) ||
                   m_generation.load(std::memory_order_acquire) != seen;
        };
        if (!spinUntil(woken)) {
            std::unique_lock<std::mutex> lock(m_mutex);
            m_wake.wait(lock, woken);
        }
        if (m_stop.load()) {
            return;
        }
        seen = m_generation.load(std::memory_order_acquire);
        runRanges(worker);
        if (m_busy.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // The caller may be asleep in finishTask: take the lock so that the notification
            // cannot fall between its check and its wait.
            std::lock_guard<std::mutex> lock(m_mutex);
            m_done.notify_one();
        }
    }
}

} // namespace fluid
