// Shared helpers of the binding files: conversions of OCCT values to Python
// tuples and the single place where a failed Status becomes an exception.
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <new>
#include <string>
#include <vector>

#include <Standard_Failure.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/errors.h"

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

// Runs `work` (which must not touch Python objects) without the GIL, so
// FreeCAD's GUI and other Python threads go on meanwhile.
template <class Work>
auto without_gil(Work&& work) {
  py::gil_scoped_release release;
  return work();
}

// Raises contactcore.ContactsError (a RuntimeError) with Status::describe().
void raise_if_failed(const Status& status);

// Runs `work` (returning a Status) with the GIL released and any OCCT or C++
// exception turned into a Status, so nothing escapes into FreeCAD as a crash.
template <class Work>
Status guarded(Work&& work) {
  py::gil_scoped_release release;
  try {
    return work();
  } catch (const Standard_Failure& failure) {
    // Some OCCT exceptions carry no message: name their type then.
    const char* text = failure.GetMessageString();
    return Status::failure(StatusCode::GeometryError, std::string("OCCT ") + failure.DynamicType()->Name() +
                                                          (text && *text ? std::string(": ") + text : ""));
  } catch (const std::bad_alloc&) {
    return Status::failure(StatusCode::GeometryError, "out of memory");
  } catch (const std::exception& error) {
    return Status::failure(StatusCode::GeometryError,
                           *error.what() ? error.what() : "C++ exception without a message");
  }
}

}  // namespace contactcore::bindings
