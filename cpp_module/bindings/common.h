// Shared helpers of the binding files: conversions of OCCT values to Python
// tuples and the single place where a failed Status becomes an exception.
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <new>
#include <string>
#include <vector>

#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/common/errors.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/partitions/partitions.h"
#include "read_only_getters.h"

namespace contactcore::bindings {

namespace py = pybind11;

inline py::tuple to_tuple(const gp_Pnt& p) { return py::make_tuple(p.X(), p.Y(), p.Z()); }
inline py::tuple to_tuple(const gp_Dir& d) { return py::make_tuple(d.X(), d.Y(), d.Z()); }

// FreeCAD's sub-element names of 1-based face indices: "Face3".
inline std::vector<std::string> face_names(const std::vector<int>& faces) {
  std::vector<std::string> names;
  names.reserve(faces.size());
  for (int f : faces) names.push_back("Face" + std::to_string(f));
  return names;
}

// Calls a Python callable(stage, fraction) -> bool from the thread that called
// the core (which runs without the GIL; its workers never call it). An
// exception raised by the callback (or a return value that is not a truth
// value) stops the work and is re-raised as is once the core has returned:
// KeyboardInterrupt and SystemExit too.
class PythonProgress : public Progress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {
    if (!PyCallable_Check(callback_.ptr()))
      throw py::type_error("progress must be callable(stage, fraction), not " +
                           std::string(py::str(py::type::of(callback_).attr("__name__"))));
  }
  bool report(const char* stage, double fraction) override {
    py::gil_scoped_acquire gil;
    if (raised_) return false;
    try {
      py::object answer = callback_(stage, fraction);
      return answer.is_none() || answer.cast<bool>();
    } catch (...) {
      raised_ = std::current_exception();
      return false;
    }
  }
  // With the GIL held.
  void rethrow_if_raised() {
    if (raised_) std::rethrow_exception(std::exchange(raised_, nullptr));
  }

 private:
  py::object callback_;
  std::exception_ptr raised_;
};

// Raises the module's exception class of status.code (bind_errors.cpp; every
// class a contactcore.ContactsError) with Status::describe().
void raise_if_failed(const Status& status);

// Runs `work` (returning a Status) with the GIL released and any OCCT or C++
// exception turned into a Status (status_of_current_exception: OCCT failures
// GeometryError, out of memory OutOfMemory, anything else Internal), so
// nothing escapes into FreeCAD as a crash. Every binding that runs core code
// goes through here (or through call_guarded below).
template <class Work>
Status guarded(Work&& work) {
  py::gil_scoped_release release;
  return status_of(std::forward<Work>(work));
}

// Runs `work` (returning a value, not a Status; it must not touch Python
// objects) through guarded(): its value, or the failure raised as the
// module's exception.
template <class Work>
auto call_guarded(Work&& work) {
  using Value = std::decay_t<decltype(work())>;
  if constexpr (std::is_void_v<Value>) {
    raise_if_failed(guarded([&] {
      work();
      return Status::success();
    }));
  } else {
    std::optional<Value> value;
    raise_if_failed(guarded([&] {
      value.emplace(work());
      return Status::success();
    }));
    return std::move(*value);
  }
}

// Raises ArgumentError (InvalidArgument): a bad value of a binding's argument.
[[noreturn]] inline void raise_argument_error(const std::string& message) {
  raise_if_failed(Status::failure(StatusCode::InvalidArgument, message));
  throw std::logic_error("unreachable: raise_if_failed returned on a failure");
}

// Partitions one body and builds `out = build(shape, partitions)` (a result
// with a `status`) under OCCT's signal guard: the first failure, of either
// step or a signal, named after the body.
template <class Result, class Build>
Status partition_and_build(const Body& body, const Tolerances& tolerances, Result& out, Build&& build) {
  Status status;
  std::string failure;
  if (!run_guarded([&] {
        const BodyPartitions partitions = partition_shape(body.shape, tolerances);
        status = partitions.status;
        if (status.ok()) {
          out = build(body.shape, partitions);
          status = out.status;
        }
      }, failure, "OCCT: "))
    status = Status::failure(StatusCode::GeometryError, failure);
  if (!status.ok()) status.body = body.name;
  return status;
}

}  // namespace contactcore::bindings
