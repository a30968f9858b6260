#pragma once
// The parts of the _busdecode module, each binding its own functions and classes, and
// what they share: the errors and the decoder requests.
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "core/session.h"

namespace busdecode::py {

namespace pyb = pybind11;

// A wrong call (unknown decoder, option, role; a bad argument): busdecode.UsageError.
// Bad input (the capture, the rules file) stays busdecode::InputError:
// busdecode.InputError. Both carry the line `decode` prints after "decode: ".
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// --proto/--map/--opt as the CLI takes them ("ROLE=SIGNAL", "KEY=VALUE", optionally
// scoped "proto.KEY=VALUE"), with the plugins they need loaded. Throws UsageError.
std::vector<DecoderRequest> requestsFor(const std::vector<std::string>& protos,
                                        const std::vector<std::string>& maps,
                                        const std::vector<std::string>& opts);

// Whether Python has begun to finalize: it then ends a daemon thread that takes the GIL
// back with pthread_exit, and that unwinding aborts the process at the first C++
// destructor it meets ("terminate called without an active exception").
inline bool pythonFinalizing() {
#if PY_VERSION_HEX >= 0x030D0000
    return Py_IsFinalizing() != 0;
#else
    return _Py_IsFinalizing() != 0;
#endif
}

// The thread Python runs and finalizes on (threading.main_thread()), noted at import:
// it takes the GIL back while finalizing, as ever (a module global's iterator closes).
void noteMainThread();
bool onMainThread();

// Runs `f` (which must not touch Python) with the GIL released, then takes it back. A
// thread that Python finalizes meanwhile instead runs `stop_work` (which ends and joins
// what it started) and waits for the process to exit, as Python 3.14 does with such
// threads itself.
template <class F, class StopWork>
void withoutGil(F&& f, StopWork&& stop_work) {
    PyThreadState* saved = PyEval_SaveThread();
    const auto retake = [&] {
        if (pythonFinalizing() && !onMainThread()) {
            stop_work();
            for (;;)
                ::pause();
        }
        PyEval_RestoreThread(saved);
    };
    try {
        f();
    } catch (...) {
        retake();
        throw;
    }
    retake();
}

// Runs `wait` (which must not touch Python) with the GIL released until it returns true;
// between its calls, Ctrl-C raises KeyboardInterrupt. `stop_work`: as for withoutGil.
template <class Wait, class StopWork>
void waitInterruptibly(Wait&& wait, StopWork&& stop_work) {
    for (;;) {
        bool ready = false;
        withoutGil([&] { ready = wait(); }, stop_work);
        if (ready) return;
        if (PyErr_CheckSignals() != 0) throw pyb::error_already_set();
    }
}

// Runs `work(stop)` on a thread of its own while this one waits with the GIL released, so
// that Ctrl-C raises KeyboardInterrupt at once (read(), verify()): `stop` is then set,
// and the work, which polls it, is waited for before the exception goes on. The work's
// own exception is rethrown here. `work` must not touch Python.
template <class Work>
void runInterruptibly(Work&& work) {
    std::atomic<bool> stop{false};
    std::exception_ptr error;
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
    std::thread worker([&] {
        try {
            work(stop);
        } catch (...) {
            error = std::current_exception();
        }
        const std::lock_guard<std::mutex> lock(mu);
        done = true;
        cv.notify_all();
    });
    const auto stopWork = [&] {
        stop = true;
        if (worker.joinable()) worker.join();
    };
    try {
        waitInterruptibly(
            [&] {
                std::unique_lock<std::mutex> lock(mu);
                return cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; });
            },
            stopWork);
    } catch (...) {
        withoutGil(stopWork, [] {});
        throw;
    }
    worker.join();
    if (error) std::rethrow_exception(error);
}

void bindErrors(pyb::module_& m);
void bindDecoders(pyb::module_& m);
void bindDecode(pyb::module_& m);
void bindRead(pyb::module_& m);
void bindVerify(pyb::module_& m);
void bindSubscribe(pyb::module_& m);

}  // namespace busdecode::py
