#include <Standard_Version.hxx>

#include "common.h"

namespace contactcore::bindings {

namespace {
py::object& contacts_error() {
  static py::object error;
  return error;
}
py::object& cancelled_error() {
  static py::object error;
  return error;
}
py::object& input_error() {
  static py::object error;
  return error;
}
py::object& argument_error() {
  static py::object error;
  return error;
}

const py::object& memory_error() {
  static const py::object error = py::reinterpret_borrow<py::object>(PyExc_MemoryError);
  return error;
}

const py::object& error_type(StatusCode code) {
  switch (code) {
    case StatusCode::Cancelled: return cancelled_error();
    case StatusCode::InvalidInput:
    case StatusCode::ReadError: return input_error();
    case StatusCode::InvalidArgument: return argument_error();
    case StatusCode::OutOfMemory: return memory_error();
    default: return contacts_error();
  }
}
}  // namespace

void raise_if_failed(const Status& status) {
  if (status.ok()) return;
  // Never an empty message; paths and OCCT texts may not be UTF-8.
  const std::string text = status.describe();
  PyObject* message = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "backslashreplace");
  if (!message) throw py::error_already_set();
  PyErr_SetObject(error_type(status.code).ptr(), message);
  Py_DECREF(message);
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  contacts_error() = py::reinterpret_borrow<py::object>(
      py::handle(PyErr_NewException("contactcore.ContactsError", PyExc_RuntimeError, nullptr)));
  m.attr("ContactsError") = contacts_error();
  cancelled_error() = py::reinterpret_borrow<py::object>(
      py::handle(PyErr_NewException("contactcore.Cancelled", contacts_error().ptr(), nullptr)));
  m.attr("Cancelled") = cancelled_error();
  // A file that cannot be read or holds no usable solid.
  input_error() = py::reinterpret_borrow<py::object>(
      py::handle(PyErr_NewException("contactcore.InputError", contacts_error().ptr(), nullptr)));
  m.attr("InputError") = input_error();
  // An argument out of range (also a ValueError).
  argument_error() = py::reinterpret_borrow<py::object>(py::handle(PyErr_NewException(
      "contactcore.ArgumentError", py::make_tuple(contacts_error(), py::handle(PyExc_ValueError)).ptr(), nullptr)));
  m.attr("ArgumentError") = argument_error();
  m.attr("OCC_VERSION") = OCC_VERSION_COMPLETE;
}

}  // namespace contactcore::bindings
