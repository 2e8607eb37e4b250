// fluid tests — the default thread pool runs every item of every task exactly once: tasks back
// to back (its threads spinning between them) and after pauses longer than its spin (its
// threads asleep), of every size from none to many ranges, while another thread keeps a core
// busy. A lost wake-up would hang here (ctest's timeout fails it).
#include <fluid/task.h>

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

using namespace fluid;

namespace {

struct Counts {
    std::vector<std::atomic<uint32_t>> hits;
    std::atomic<uint32_t> badWorker{0};
    uint32_t workers = 0;
    explicit Counts(size_t n) : hits(n) {}
};

void countRange(uint32_t begin, uint32_t end, uint32_t worker, void* context) {
    auto& counts = *static_cast<Counts*>(context);
    if (worker >= counts.workers) {
        counts.badWorker.fetch_add(1);
    }
    for (uint32_t i = begin; i < end; ++i) {
        counts.hits[i].fetch_add(1, std::memory_order_relaxed);
    }
}

} // namespace

TEST_CASE("the thread pool runs every item of every task exactly once, awake or asleep",
          "[threads]") {
    constexpr uint32_t kMaxItems = 5000;
    std::atomic<bool> busyStop{false};
    // Another thread on a core: the pool's threads get preempted now and then.
    std::thread busy([&] {
        volatile uint64_t x = 0;
        while (!busyStop.load(std::memory_order_relaxed)) {
            x = x + 1;
        }
    });
    for (const uint32_t workers : {2u, 4u}) {
        ThreadPool pool(workers);
        const TaskHook hook = pool.hook();
        Counts counts(kMaxItems);
        counts.workers = hook.workerCount;
        std::mt19937 random(workers);
        uint32_t wrong = 0;
        for (int task = 0; task < 4000; ++task) {
            const uint32_t items = random() % kMaxItems;
            const uint32_t minRange = 1 + random() % 300;
            for (uint32_t i = 0; i < items; ++i) {
                counts.hits[i].store(0, std::memory_order_relaxed);
            }
            void* token = hook.enqueue(countRange, items, minRange, &counts, hook.userContext);
            if (token != nullptr) {
                hook.finish(token, hook.userContext);
            }
            for (uint32_t i = 0; i < items; ++i) {
                wrong += counts.hits[i].load(std::memory_order_relaxed) == 1 ? 0 : 1;
            }
            // Every 50th task after a pause longer than the pool's spin: its threads sleep.
            if (task % 50 == 49) {
                std::this_thread::sleep_for(std::chrono::microseconds(300));
            }
        }
        INFO("workers " << workers);
        CHECK(wrong == 0);
        CHECK(counts.badWorker.load() == 0);
    }
    busyStop.store(true);
    busy.join();
}
