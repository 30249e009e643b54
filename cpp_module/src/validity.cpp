#include "contactcore/validity.h"

#include <BRepCheck_Status.hxx>
#include <BRepCheck_Wire.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include "contactcore/parallel.h"

namespace contactcore {

namespace {

// FaceN of the faces whose wires cross themselves.
std::vector<int> self_intersecting_faces(const BodyPartitions& body) {
  std::vector<int> faces;
  for (const FaceInfo& info : body.faces) {
    for (TopExp_Explorer w(info.face, TopAbs_WIRE); w.More(); w.Next()) {
      Handle(BRepCheck_Wire) check = new BRepCheck_Wire(TopoDS::Wire(w.Current()));
      TopoDS_Edge first, second;
      if (check->SelfIntersect(info.face, first, second, Standard_False) != BRepCheck_NoError) {
        faces.push_back(info.index);
        break;
      }
    }
  }
  return faces;
}

std::string face_list(const std::vector<int>& faces) {
  std::string text;
  for (int f : faces) text += (text.empty() ? "Face" : ", Face") + std::to_string(f);
  return text;
}

}  // namespace

Status check_solids(const Assembly& assembly, ContactsResult& result, Progress* progress, int threads) {
  const std::size_t n = result.partitions.size();
  const auto source_of = [&](std::size_t i) {
    return i < result.instance_of.size() ? static_cast<std::size_t>(result.instance_of[i]) : i;
  };
  std::vector<std::vector<int>> faces(n);
  std::vector<std::string> failures(n);
  if (!parallel_for(n, threads, progress, "checking solids", [&](std::size_t i) {
        if (source_of(i) != i) return;
        try {
          faces[i] = self_intersecting_faces(result.partitions[i]);
        } catch (const Standard_Failure& failure) {
          failures[i] = std::string("its check failed: ") + failure.GetMessageString();
        }
      }))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t source = source_of(i);
    const std::string& name = assembly.bodies[i].name;
    if (!failures[source].empty()) {
      result.messages.push_back("body '" + name + "': " + failures[source]);
      continue;
    }
    if (faces[source].empty()) continue;
    InvalidBody invalid{static_cast<int>(i), faces[source], "self-intersecting boundary"};
    result.messages.push_back("body '" + name + "' is not a valid solid: " + invalid.reason + " (" +
                              face_list(invalid.faces) + "); its contacts and areas may be wrong");
    result.invalid_bodies.push_back(std::move(invalid));
  }
  return Status::success();
}

}  // namespace contactcore
