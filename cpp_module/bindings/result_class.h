// Result classes of the bindings: read-only documented properties and a
// to_dict() for JSON output, both from one list of fields, so a field added
// to a result is one `.field(...)` line (its property, its docstring and its
// place in to_dict() together).
// Each property's getter goes through the one function binding of
// read_only_getters.h (haptic_results.cpp compiles in a sixth less CPU).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <pybind11/pybind11.h>

#include "read_only_getters.h"

namespace contactcore::bindings {

namespace py = pybind11;

// The plain-Python form of a field's value: a result (anything with
// to_dict) as its dict, lists and tuples element by element (as lists, as
// JSON writes them), None and scalars as they are.
inline py::object plain_value(const py::handle& value) {
  if (value.is_none()) return py::none();
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    py::list out;
    for (const py::handle& item : value) out.append(plain_value(item));
    return std::move(out);
  }
  if (py::hasattr(value, "to_dict")) return value.attr("to_dict")();
  return py::reinterpret_borrow<py::object>(value);
}

template <class Result>
class ResultClass {
 public:
  ResultClass(py::handle scope, const char* name, const char* doc)
      : class_(scope, name, doc), fields_(std::make_shared<std::vector<Field>>()) {}

  // A member of Result, as it is (Vec3 and the like need a getter); as
  // def_readonly gives it: a reference into the result, which it keeps alive.
  template <class Member>
  ResultClass& field(const char* name, Member Result::*member, const char* doc) {
    return add(name, name, [member](const py::handle& self) {
      return as_object(self.cast<const Result&>().*member, self);
    }, doc);
  }

  // A value computed from Result: getter(const Result&).
  template <class Getter>
  ResultClass& field(const char* name, Getter&& getter, const char* doc) {
    return field(name, name, std::forward<Getter>(getter), doc);
  }

  // A field whose to_dict() key is not a Python name ("with"): the property
  // is `name`, the key `key`.
  template <class Getter>
  ResultClass& field(const char* name, const char* key, Getter&& getter, const char* doc) {
    return add(name, key, [getter = std::forward<Getter>(getter)](const py::handle& self) {
      return as_object(getter(self.cast<const Result&>()), self);
    }, doc);
  }

  // Adds to_dict(), `fields` and __repr__; the class for further .def calls.
  py::class_<Result>& done() {
    auto fields = fields_;
    py::tuple names(fields->size());
    for (std::size_t i = 0; i < fields->size(); ++i) names[i] = py::str((*fields)[i].property);
    class_.attr("fields") = names;
    class_.def(
        "to_dict",
        [fields](const py::object& self) {
          py::dict out;
          for (const Field& f : *fields) out[py::str(f.key)] = plain_value(self.attr(f.property.c_str()));
          return out;
        },
        "The fields as a dict of plain Python values (nested results as dicts), in the order of `fields` "
        "(with_body under the key 'with'): what JSON output writes.");
    class_.def("__repr__", [](const py::object& self) {
      return "<" + std::string(py::str(py::type::of(self).attr("__name__"))) + " " +
             std::string(py::repr(self.attr("to_dict")())) + ">";
    });
    return class_;
  }

 private:
  ResultClass& add(const char* name, const char* key, FieldGetter get, const char* doc) {
    class_.def_property_readonly(name, field_getter(std::move(get)), doc);
    fields_->push_back({name, key});
    return *this;
  }

  struct Field {
    std::string property, key;
  };
  py::class_<Result> class_;
  std::shared_ptr<std::vector<Field>> fields_;
};

}  // namespace contactcore::bindings
