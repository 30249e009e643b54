// The `contactcore` Python extension: thin bindings of the C++ core, one file
// per pipeline area. FreeCAD shapes cross as BRep text (exportBrepToString).
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace contactcore::bindings {
void bind_errors(py::module_& m);
void bind_bodies(py::module_& m);
void bind_partitions(py::module_& m);
void bind_contacts(py::module_& m);
void bind_joints(py::module_& m);
void bind_meshes(py::module_& m);
void bind_collision(py::module_& m);
void bind_disassembly(py::module_& m);
void bind_simplify(py::module_& m);
#ifdef CONTACTS_WITH_HAPTICS
void bind_haptics(py::module_& m);
#endif
}  // namespace contactcore::bindings

PYBIND11_MODULE(contactcore, m) {
  m.doc() = "Contacts workbench core: bodies, partitions, contacts (OCCT 7.6)";
  using namespace contactcore::bindings;
  bind_errors(m);
  bind_bodies(m);
  bind_partitions(m);
  bind_contacts(m);
  bind_joints(m);
  bind_meshes(m);
  bind_collision(m);
  bind_disassembly(m);
  bind_simplify(m);
#ifdef CONTACTS_WITH_HAPTICS
  bind_haptics(m);
#endif
}
