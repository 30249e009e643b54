// The module's exceptions: one class per StatusCode, every one a
// contactcore.ContactsError (a RuntimeError), raised by raise_if_failed only.
#include <Standard_Version.hxx>

#include <array>

#include "common.h"

namespace contactcore::bindings {

namespace {

// What each failed StatusCode raises, in the order of the enum (Ok excluded).
struct ErrorClass {
  StatusCode code;
  const char* name;
  const char* doc;
};
constexpr std::array<ErrorClass, 7> kErrorClasses{{
    {StatusCode::InvalidInput, "InputError", "A file or shape that cannot be used: empty, unreadable BRep, no solid."},
    {StatusCode::ReadError, "ReadError", "A file that cannot be opened or parsed (also an InputError)."},
    {StatusCode::GeometryError, "GeometryError", "OCCT failed on a body or face (the message names them)."},
    {StatusCode::Cancelled, "Cancelled", "The progress callback asked to stop."},
    {StatusCode::InvalidArgument, "ArgumentError",
     "An argument or keyword option out of range or misspelt (also a ValueError)."},
    {StatusCode::OutOfMemory, "OutOfMemoryError", "The core ran out of memory (also a MemoryError)."},
    {StatusCode::Internal, "InternalError", "A C++ exception the core did not expect: a bug, please report it."},
}};

py::object& contacts_error() {
  static py::object error;
  return error;
}

// Indexed by StatusCode.
std::array<py::object, 8>& error_types() {
  static std::array<py::object, 8> types;
  return types;
}

const py::object& error_type(StatusCode code) {
  const auto index = static_cast<std::size_t>(code);
  const py::object& type = index < error_types().size() ? error_types()[index] : contacts_error();
  return type ? type : contacts_error();
}

// The bases of one class: ContactsError, and the Python built-in it also is.
py::tuple bases_of(StatusCode code) {
  switch (code) {
    case StatusCode::ReadError: return py::make_tuple(error_type(StatusCode::InvalidInput));
    case StatusCode::InvalidArgument: return py::make_tuple(contacts_error(), py::handle(PyExc_ValueError));
    case StatusCode::OutOfMemory: return py::make_tuple(contacts_error(), py::handle(PyExc_MemoryError));
    default: return py::make_tuple(contacts_error());
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
  contacts_error() = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "contactcore.ContactsError", "Base of every exception of the module (a RuntimeError).", PyExc_RuntimeError,
      nullptr));
  if (!contacts_error()) throw py::error_already_set();
  m.attr("ContactsError") = contacts_error();
  for (const ErrorClass& error : kErrorClasses) {
    const std::string qualified = std::string("contactcore.") + error.name;
    py::object type = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc(qualified.c_str(), error.doc, bases_of(error.code).ptr(), nullptr));
    if (!type) throw py::error_already_set();
    error_types()[static_cast<std::size_t>(error.code)] = type;
    m.attr(error.name) = type;
  }

  py::enum_<StatusCode>(m, "StatusCode", "Why a core call failed; exception_for(code) is the class it raises.")
      .value("Ok", StatusCode::Ok)
      .value("InvalidInput", StatusCode::InvalidInput)
      .value("ReadError", StatusCode::ReadError)
      .value("GeometryError", StatusCode::GeometryError)
      .value("Cancelled", StatusCode::Cancelled)
      .value("InvalidArgument", StatusCode::InvalidArgument)
      .value("OutOfMemory", StatusCode::OutOfMemory)
      .value("Internal", StatusCode::Internal);
  m.def(
      "exception_for",
      [](StatusCode code) -> py::object {
        if (code == StatusCode::Ok) return py::none();
        return error_type(code);
      },
      py::arg("code"), "The exception class a failure with this StatusCode raises (None for Ok).");
  m.attr("OCC_VERSION") = OCC_VERSION_COMPLETE;
}

}  // namespace contactcore::bindings
