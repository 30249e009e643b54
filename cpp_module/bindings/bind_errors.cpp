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
}  // namespace

void raise_if_failed(const Status& status) {
  if (status.ok()) return;
  const py::object& type = status.code == StatusCode::Cancelled ? cancelled_error() : contacts_error();
  PyErr_SetString(type.ptr(), status.describe().c_str());
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  contacts_error() = py::reinterpret_borrow<py::object>(
      py::handle(PyErr_NewException("contactcore.ContactsError", PyExc_RuntimeError, nullptr)));
  m.attr("ContactsError") = contacts_error();
  cancelled_error() = py::reinterpret_borrow<py::object>(
      py::handle(PyErr_NewException("contactcore.Cancelled", contacts_error().ptr(), nullptr)));
  m.attr("Cancelled") = cancelled_error();
  m.attr("OCC_VERSION") = OCC_VERSION_COMPLETE;
}

}  // namespace contactcore::bindings
