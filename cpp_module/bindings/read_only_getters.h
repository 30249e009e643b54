// Read-only properties through one pybind11 function binding. pybind11 makes
// a dispatcher, argument loaders and a signature for each function type it
// binds: one per property (a def_readonly per member type, a lambda each)
// was most of the bindings' compile time. Here every getter is a FieldGetter,
// called by the one binding of field_getter(); a property costs a
// std::function (haptic_results.cpp, -O1, no precompiled header, cold: 29.1 s of
// CPU before, 24.5 s after; 26 Nov 2026, the shared machine).
// The value is converted as pybind11's own property would: reference_internal,
// the holding object kept alive by what it returns.
#pragma once

#include <functional>
#include <type_traits>
#include <utility>

#include <pybind11/pybind11.h>

namespace contactcore::bindings {

namespace py = pybind11;

// A property's getter: the object holding the value -> the value.
using FieldGetter = std::function<py::object(const py::handle& self)>;

// The one pybind11 function binding of every read-only property's getter.
inline py::cpp_function field_getter(FieldGetter get) {
  return py::cpp_function([get = std::move(get)](const py::handle& self) { return get(self); });
}

// A getter's value as a Python object, as a def_property_readonly getter
// returns it (a Python object as it is).
template <class Value>
py::object as_object(Value&& value, const py::handle& self) {
  if constexpr (std::is_base_of_v<py::handle, std::decay_t<Value>>)
    return py::reinterpret_borrow<py::object>(value);
  else
    return py::cast(std::forward<Value>(value), py::return_value_policy::reference_internal, self);
}

// The getter of a data member, for def_property_readonly (as def_readonly:
// `.def_property_readonly("x", read_only(&T::x), "doc")`).
template <class Class, class Member>
py::cpp_function read_only(Member Class::*member) {
  return field_getter([member](const py::handle& self) { return as_object(self.cast<const Class&>().*member, self); });
}

}  // namespace contactcore::bindings
