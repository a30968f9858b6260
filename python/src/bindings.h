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

// Runs `wait` (which must not touch Python) with the GIL released, in slices of
// `slice_ms`, until it returns true; between slices, Ctrl-C raises KeyboardInterrupt.
template <class Wait>
void waitInterruptibly(Wait&& wait) {
    for (;;) {
        bool ready;
        {
            pyb::gil_scoped_release nogil;
            ready = wait();
        }
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
    try {
        waitInterruptibly([&] {
            std::unique_lock<std::mutex> lock(mu);
            return cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; });
        });
    } catch (...) {
        stop = true;
        pyb::gil_scoped_release nogil;
        worker.join();
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
