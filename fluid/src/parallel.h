// fluid — running stage loops on the host's task hook.
#pragma once

#include <fluid/task.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fluid::detail {

/// Runs `f(begin, end, worker)` over [0, count) through `hook`, or inline when it has no
/// enqueue or the work is small. Every stage writes only its own range, so the split does not
/// change results.
template <class F>
void parallelFor(const TaskHook& hook, uint32_t count, uint32_t minRange, F&& f) {
    if (count == 0) {
        return;
    }
    if (hook.enqueue == nullptr || hook.workerCount <= 1 || count <= minRange) {
        f(0u, count, 0u);
        return;
    }
    using Fn = std::remove_reference_t<F>;
    TaskCallback* callback = [](uint32_t begin, uint32_t end, uint32_t worker, void* context) {
        (*static_cast<Fn*>(context))(begin, end, worker);
    };
    void* task = hook.enqueue(callback, count, minRange,
                              const_cast<void*>(static_cast<const void*>(&f)), hook.userContext);
    if (task != nullptr) {
        hook.finish(task, hook.userContext);
    }
}

/// Fixed block size of deterministic reductions (independent of the worker count).
inline constexpr uint32_t kReduceBlock = 2048;

/// Deterministic reduction: `partial(begin, end)` over fixed blocks of `kReduceBlock` items,
/// combined in block order with `combine`. Same result for any number of workers.
template <class T, class Partial, class Combine>
T blockReduce(const TaskHook& hook, uint32_t count, T init, Partial&& partial, Combine&& combine) {
    const uint32_t blocks = (count + kReduceBlock - 1) / kReduceBlock;
    std::vector<T> partials(blocks, init);
    parallelFor(hook, blocks, 1, [&](uint32_t b0, uint32_t b1, uint32_t) {
        for (uint32_t b = b0; b < b1; ++b) {
            const uint32_t begin = b * kReduceBlock;
            partials[b] = partial(begin, std::min(count, begin + kReduceBlock));
        }
    });
    T result = init;
    for (const T& value : partials) {
        result = combine(result, value);
    }
    return result;
}

} // namespace fluid::detail
