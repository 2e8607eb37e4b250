// fluid — the default thread pool.
#include <fluid/error.h>
#include <fluid/task.h>

#include <algorithm>
#include <string>

namespace fluid {

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
        m_stop = true;
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
        pool->m_busy = static_cast<uint32_t>(pool->m_threads.size());
        ++pool->m_generation;
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
    std::unique_lock<std::mutex> lock(pool->m_mutex);
    pool->m_done.wait(lock, [pool] { return pool->m_busy == 0; });
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
        {
            std::unique_lock<std::mutex> lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stop || m_generation != seen; });
            if (m_stop) {
                return;
            }
            seen = m_generation;
        }
        runRanges(worker);
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            --m_busy;
        }
        m_done.notify_one();
    }
}

} // namespace fluid
