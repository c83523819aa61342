#pragma once
// The studies' runs are independent and deterministic: `jobs` threads take them in turn, and the
// results do not depend on how many run at once.
#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace pba::study {

/// run(i) for every i < total on `jobs` threads; `progress(done, total)` from the calling thread
/// every 50 ms and at the end. The first run that throws is rethrown once every thread has joined.
inline void runInParallel(std::size_t total, int jobs, const std::function<void(std::size_t)>& run,
                          const std::function<void(long, long)>& progress)
{
    std::atomic<std::size_t> next{0};
    std::atomic<long> done{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto worker = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < total; ++done) try {
            run(i);
        } catch (...) {
            const std::lock_guard lock(failureMutex);
            if (!failure)
                failure = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    for (int j = 1; j < std::max(1, jobs); ++j)
        threads.emplace_back(worker);
    std::thread main(worker);
    while (done.load() < static_cast<long>(total)) {
        if (progress)
            progress(done.load(), static_cast<long>(total));
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    main.join();
    for (auto& t : threads)
        t.join();
    if (failure)
        std::rethrow_exception(failure);
    if (progress)
        progress(static_cast<long>(total), static_cast<long>(total));
}

} // namespace pba::study
