// Runs long C++ work with the GIL released on a worker thread while the calling thread wakes
// every 100 ms to check for Ctrl-C and to call the progress callback. Ctrl-C or an exception in
// the callback sets the cancel flag; the work stops at its next check and returns what it has.
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
};

template <class Work>
auto run_interruptible(const Work& work, RenderControl& control, const py::object& progress)
    -> Interruptible<decltype(work())> {
  using Result = decltype(work());
  std::optional<Result> result;
  std::exception_ptr failure;
  std::optional<py::error_already_set> callback_error;
  bool keyboard_interrupt = false;
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;

  auto report = [&] {
    if (progress.is_none() || callback_error) return;
    try {
      progress(control.done.load(), control.total.load());
    } catch (py::error_already_set& e) {
      callback_error.emplace(std::move(e));
      control.cancel = true;
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
          // Keep the partial result: the caller raises KeyboardInterrupt with it attached.
          PyErr_Clear();
          keyboard_interrupt = true;
          control.cancel = true;
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
  if (callback_error) throw std::move(*callback_error);
  report();
  return {std::move(*result), keyboard_interrupt};
}

}  // namespace dualight::bindings
