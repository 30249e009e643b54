// A body's volume, centre of mass and inertia tensor from OCCT's GProp.
#include "contactcore/bodies/inertia.h"

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Standard_Failure.hxx>
#include <gp_Mat.hxx>

#include "contactcore/common/occt_guard.h"

namespace contactcore {

BodyInertia body_inertia(const Body& body) {
  BodyInertia out;
  try {
    const OcctGuard guard;  // a signal inside OCCT's integration: a failure, not a crash
    GProp_GProps props;
    with_occt_signals([&] { BRepGProp::VolumeProperties(body.shape, props); });
    out.volume = props.Mass();
    const gp_Pnt centre = props.CentreOfMass();
    out.centre = {centre.X(), centre.Y(), centre.Z()};
    // GProp gives the matrix about the centre of mass (its own docs), in the shape's (global) axes.
    const gp_Mat m = props.MatrixOfInertia();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out.tensor[i][j] = m.Value(i + 1, j + 1);
    if (!(out.volume > 0)) {
      out.status = Status::failure(StatusCode::GeometryError, "no volume (an open or inverted solid)");
      out.status.body = body.name;
    }
  } catch (const Standard_Failure& failure) {
    out.status = Status::failure(StatusCode::GeometryError, "inertia failed: OCCT: " + occt_failure_text(failure));
    out.status.body = body.name;
  } catch (...) {
    out.status = status_of_current_exception();
    out.status.body = body.name;
  }
  return out;
}

}  // namespace contactcore
