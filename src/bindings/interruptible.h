// Runs long C++ work with the GIL released on a worker thread while the calling thread wakes
// every 100 ms to check for Python signals and to call the progress callback. Ctrl-C, another
// exception from a signal handler or an exception in the callback sets the cancel flag; the
// work stops at its next check and returns what it has, which goes back to Python on the
// KeyboardInterrupt (keyboard_interrupt) or on the exception raised (finished()).
#pragma once
#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "core/render_control.h"

namespace dualight::bindings {

namespace py = pybind11;

template <class Result>
struct Interruptible {
  Result result;
  bool keyboard_interrupt = false;
  // An exception other than Ctrl-C's KeyboardInterrupt that a Python signal handler (SIGALRM
  // raising its own, SIGTERM raising SystemExit) or the progress callback raised: the work
  // stopped there, and the binding raises it again with the partial result (finished()).
  std::optional<py::error_already_set> raised;
};

namespace detail {

// Ctrl-C (KeyboardInterrupt) keeps its partial result through `keyboard_interrupt`; any other
// exception is kept to be raised again. Either cancels the work.
inline void keep(py::error_already_set&& e, bool& keyboard_interrupt,
                 std::optional<py::error_already_set>& raised, RenderControl& control) {
  if (e.matches(PyExc_KeyboardInterrupt)) {
    keyboard_interrupt = true;
  } else if (!raised) {
    raised.emplace(std::move(e));
  }
  control.cancel = true;
}

}  // namespace detail

// `result` (the binding's Python form of run.result), or run.raised raised again with `result`
// as its `partial_result` (None where nothing partial is worth keeping).
// Returns `result` as the type it came as (py::dict keeps the stubs' return types precise).
template <class Result, class Python>
Python finished(Interruptible<Result>& run, Python result) {
  if (!run.raised) return result;
  if (!result.is_none()) {
    try {
      run.raised->value().attr("partial_result") = result;
    } catch (py::error_already_set&) {  // an exception object without attributes: raised as it is
    }
  }
  throw std::move(*run.raised);
}

template <class Work>
auto run_interruptible(const Work& work, RenderControl& control, const py::object& progress)
    -> Interruptible<decltype(work())> {
  using Result = decltype(work());
  std::optional<Result> result;
  std::exception_ptr failure;
  std::optional<py::error_already_set> raised;
  bool keyboard_interrupt = false;
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;

  auto report = [&] {
    if (progress.is_none() || raised || keyboard_interrupt) return;
    try {
      progress(control.done.load(), control.total.load());
    } catch (py::error_already_set& e) {
      detail::keep(std::move(e), keyboard_interrupt, raised, control);
    }
  };

  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        result.emplace(work());
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      finished_cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished_cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; })) {
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          // What the handler raised (KeyboardInterrupt for Ctrl-C), kept with the partial result.
          detail::keep(py::error_already_set(), keyboard_interrupt, raised, control);
        } else {
          report();
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  // The last report (done == total); its exception is raised like any other (it was lost).
  if (PyErr_CheckSignals() != 0) {
    detail::keep(py::error_already_set(), keyboard_interrupt, raised, control);
  } else {
    report();
  }
  return {std::move(*result), keyboard_interrupt, std::move(raised)};
}

}  // namespace dualight::bindings
