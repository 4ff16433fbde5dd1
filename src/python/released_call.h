#pragma once
// Runs a long library call on a worker thread with the GIL released, while the calling thread
// (the one Python called from) stays responsive: it delivers progress to the Python callback,
// notices Ctrl-C (PyErr_CheckSignals only works there) and turns either into a cancel request the
// worker's Interrupter reports to the library. Python objects are only touched by the calling
// thread, with the GIL held; the worker sees plain C++ data.
#include <isodel/errors.h>
#include <isodel/interrupt.h>

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

// Hidden, as pybind11's own types: nothing here is part of a C++ API.
namespace isodel {
namespace python __attribute__((visibility("hidden"))) {

namespace py = pybind11;

/// Raised when the progress callback returned False (isodel.Cancelled on the Python side).
struct CallbackCancelled : isodel::Cancelled {
    using isodel::Cancelled::Cancelled;
};

/// The worker's Interrupter: queues progress for the calling thread and answers the cancel flag.
class QueuedInterrupter final : public Interrupter {
public:
    struct Event {
        std::string stage;
        double fraction; ///< 0..1, or -1 when the stage does not know
    };

    void start(const char* name) override { push(name ? name : "", 0.0, true); }
    void end() override { push(current(), 1.0, false); }
    bool wasInterrupted(int percent) override
    {
        if (due()) push(current(), percent < 0 ? -1.0 : percent / 100.0, false);
        return cancel.load();
    }
    bool progress(std::uint64_t done, std::uint64_t total, const char*) override
    {
        if (due()) push(current(), total > 0 ? double(done) / double(total) : -1.0, false);
        return cancel.load();
    }

    /// Takes the queued events (called by the calling thread).
    std::deque<Event> take()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(events_, {});
    }
    /// Marks the work finished and wakes the calling thread.
    void finish()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        wake_.notify_all();
    }
    /// Waits until an event, the end of the work, or \p timeout. \return true when finished.
    bool wait(std::chrono::milliseconds timeout)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait_for(lock, timeout, [this] { return done_ || !events_.empty(); });
        return done_;
    }

    std::atomic<bool> cancel{false};

private:
    // The library polls from tight loops on several threads: only one poll in 20 ms takes the
    // lock and queues an update, the others just read the cancel flag.
    bool due()
    {
        const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
        auto last = last_push_.load(std::memory_order_relaxed);
        const auto gap = std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(20));
        return now - last >= gap.count() && last_push_.compare_exchange_strong(last, now);
    }
    std::string current()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return stage_;
    }
    // Stages poll far more often than a callback needs: successive updates of one stage replace
    // each other, so the queue holds at most a few events however slow the callback is.
    void push(std::string stage, double fraction, bool new_stage)
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (new_stage) stage_ = stage;
            if (!new_stage && !events_.empty() && events_.back().stage == stage)
                events_.back().fraction = fraction;
            else
                events_.push_back({std::move(stage), fraction});
        }
        wake_.notify_all();
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<Event> events_;
    std::string stage_;
    bool done_ = false;
    std::atomic<std::chrono::steady_clock::rep> last_push_{0};
};

/// Calls \p work(Interrupter*) on a worker thread with the GIL released and returns its result.
/// Must be called with the GIL held. \p progress is None or callable(stage, fraction); returning
/// False (not None) cancels. Ctrl-C cancels and re-raises KeyboardInterrupt; an exception in the
/// callback cancels and is re-raised; the worker's exceptions are rethrown here.
template <class Work>
auto released_call(Work&& work, const py::object& progress) -> decltype(work(nullptr))
{
    using Result = decltype(work(nullptr));
    QueuedInterrupter intr;
    Result result{};
    std::exception_ptr failure;
    std::thread worker([&] {
        try {
            result = work(&intr);
        } catch (...) {
            failure = std::current_exception();
        }
        intr.finish();
    });
    std::string cancel_reason;             // set when the callback asked to stop
    std::optional<py::error_already_set> python_error; // raised by the callback or a signal handler
    {
        py::gil_scoped_release release;
        bool finished = false;
        while (!finished) {
            finished = intr.wait(std::chrono::milliseconds(50));
            auto events = intr.take();
            py::gil_scoped_acquire acquire;
            if (python_error || !cancel_reason.empty()) continue; // cancelled: wait for the worker
            if (PyErr_CheckSignals() != 0) {
                python_error.emplace(); // fetches the pending KeyboardInterrupt
                intr.cancel.store(true);
                continue;
            }
            if (progress.is_none()) continue;
            for (const auto& e : events) {
                try {
                    const py::object answer = progress(e.stage, e.fraction);
                    if (answer.ptr() == Py_False) {
                        cancel_reason = "the progress callback returned False during stage '" + e.stage + "'";
                        intr.cancel.store(true);
                        break;
                    }
                } catch (py::error_already_set& err) {
                    python_error = err;
                    intr.cancel.store(true);
                    break;
                }
            }
        }
        worker.join();
    }
    if (python_error) throw *python_error;
    if (failure) {
        try {
            std::rethrow_exception(failure);
        } catch (const isodel::Cancelled&) {
            if (!cancel_reason.empty()) throw CallbackCancelled("cancelled: " + cancel_reason);
            throw;
        }
    }
    if (!cancel_reason.empty()) throw CallbackCancelled("cancelled: " + cancel_reason);
    return result;
}

} // namespace python
} // namespace isodel
