#include "contactcore/bodies.h"

#include "contactcore/instances.h"
#include "contactcore/parallel.h"

#include <map>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

namespace contactcore {

namespace {

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return {};
  const TCollection_ExtendedString& text = name->Get();
  std::string out(static_cast<size_t>(text.LengthOfCString()), '\0');
  Standard_PCharacter buffer = out.data();
  text.ToUTF8CString(buffer);
  out.resize(std::char_traits<char>::length(out.c_str()));
  return out;
}

// Solids of a shape, in explorer order. Closed shells that no solid holds are
// turned into solids (some exporters write solids as shell-based models);
// open shells and faces are counted so the caller can report them.
struct SolidHarvest {
  std::vector<TopoDS_Shape> solids;
  int open_shells = 0;
  int loose_faces = 0;
};

SolidHarvest harvest_solids(const TopoDS_Shape& shape) {
  SolidHarvest out;
  for (TopExp_Explorer it(shape, TopAbs_SOLID); it.More(); it.Next()) out.solids.push_back(it.Current());
  for (TopExp_Explorer it(shape, TopAbs_SHELL, TopAbs_SOLID); it.More(); it.Next()) {
    const TopoDS_Shell& shell = TopoDS::Shell(it.Current());
    if (BRep_Tool::IsClosed(shell)) {
      BRepBuilderAPI_MakeSolid make(shell);
      if (make.IsDone()) {
        out.solids.push_back(make.Solid());
        continue;
      }
    }
    ++out.open_shells;
  }
  for (TopExp_Explorer it(shape, TopAbs_FACE, TopAbs_SHELL); it.More(); it.Next()) ++out.loose_faces;
  return out;
}

std::string skipped_message(const std::string& name, const SolidHarvest& h) {
  std::ostringstream msg;
  msg << "skipped in '" << name << "':";
  if (h.open_shells) msg << ' ' << h.open_shells << " open shell(s)";
  if (h.loose_faces) msg << ' ' << h.loose_faces << " face(s) outside any shell";
  msg << " (surface model, not a solid)";
  return msg.str();
}

class StepTreeWalker {
 public:
  StepTreeWalker(Handle(XCAFDoc_ShapeTool) tool, Assembly& out, Progress* progress)
      : tool_(std::move(tool)), out_(out), progress_(progress) {}

  // `instance_name`: the name of the occurrence placing this shape (STEP's
  // NEXT_ASSEMBLY_USAGE_OCCURRENCE), which tells apart the instances of one
  // product; the product's own name otherwise.
  bool walk(const TDF_Label& label, const TopLoc_Location& location, const std::string& parent_path,
            const std::string& instance_name = {}) {
    if (progress_ && !progress_->report("read", 0.5)) return false;
    std::string name = instance_name.empty() ? label_name(label) : instance_name;
    if (name.empty()) name = "Body";
    const std::string path = parent_path.empty() ? name : parent_path + "/" + name;
    if (XCAFDoc_ShapeTool::IsAssembly(label)) {
      TDF_LabelSequence components;
      XCAFDoc_ShapeTool::GetComponents(label, components);
      for (Standard_Integer i = 1; i <= components.Length(); ++i) {
        const TDF_Label& component = components.Value(i);
        TDF_Label referred;
        if (!XCAFDoc_ShapeTool::GetReferredShape(component, referred)) continue;
        const TopLoc_Location placed = location * XCAFDoc_ShapeTool::GetLocation(component);
        std::string instance = label_name(component);
        // OCCT names an unnamed occurrence after its reference ("=>[0:1:1:3]").
        if (instance.rfind("=>", 0) == 0) instance.clear();
        if (!walk(referred, placed, path, instance)) return false;
      }
      return true;
    }
    const TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
    if (shape.IsNull()) return true;
    const SolidHarvest harvest = harvest_solids(shape);
    if (harvest.open_shells || harvest.loose_faces) out_.messages.push_back(skipped_message(path, harvest));
    for (const TopoDS_Shape& solid : harvest.solids) {
      out_.bodies.push_back(Body{name, path, solid.Moved(location)});
    }
    return true;
  }

 private:
  Handle(XCAFDoc_ShapeTool) tool_;
  Assembly& out_;
  Progress* progress_;
};

void read_units(STEPCAFControl_Reader& reader, Assembly& assembly) {
  TColStd_SequenceOfAsciiString length_units, angle_units, solid_angle_units;
  reader.ChangeReader().FileUnits(length_units, angle_units, solid_angle_units);
  if (length_units.IsEmpty()) return;
  std::string unit = length_units.First().ToCString();
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::map<std::string, std::pair<std::string, double>> known = {
      {"millimetre", {"mm", 1.0}}, {"millimeter", {"mm", 1.0}}, {"mm", {"mm", 1.0}},
      {"metre", {"m", 1000.0}},    {"meter", {"m", 1000.0}},    {"m", {"m", 1000.0}},
      {"centimetre", {"cm", 10.0}}, {"centimeter", {"cm", 10.0}}, {"cm", {"cm", 10.0}},
      {"inch", {"in", 25.4}},      {"in", {"in", 25.4}},        {"foot", {"ft", 304.8}},
      {"ft", {"ft", 304.8}},       {"micrometre", {"um", 1e-3}}, {"micron", {"um", 1e-3}},
  };
  const auto found = known.find(unit);
  if (found != known.end()) {
    assembly.units = found->second.first;
    assembly.source_unit_in_mm = found->second.second;
  } else {
    assembly.units = unit;
  }
}

}  // namespace

std::vector<std::string> unique_names(const std::vector<std::string>& names) {
  std::unordered_set<std::string> used;
  // Per repeated name, the next suffix to try: every smaller one is taken
  // (and stays taken), so each name costs O(1) amortised probes.
  std::unordered_map<std::string, int> next_suffix;
  std::vector<std::string> out;
  out.reserve(names.size());
  used.reserve(names.size() * 2);
  for (const std::string& name : names) {
    if (used.insert(name).second) {
      out.push_back(name);
      continue;
    }
    int& n = next_suffix.try_emplace(name, 2).first->second;
    std::string candidate;
    do candidate = name + "." + std::to_string(n++);
    while (!used.insert(candidate).second);
    out.push_back(std::move(candidate));
  }
  return out;
}

void make_names_unique(std::vector<Body>& bodies) {
  std::vector<std::string> names;
  names.reserve(bodies.size());
  for (const Body& body : bodies) names.push_back(body.name);
  names = unique_names(names);
  for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].name = std::move(names[i]);
}

AssemblyResult read_step(const std::string& path, Progress* progress) {
  AssemblyResult result;
  try {
    if (progress && !progress->report("read", 0.0)) {
      result.status = Status::failure(StatusCode::Cancelled, "cancelled");
      return result;
    }
    // Shapes come out in millimetres whatever the file's unit.
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
    Handle(TDocStd_Document) doc;
    app->NewDocument("MDTV-XCAF", doc);
    STEPCAFControl_Reader reader;
    reader.SetNameMode(true);
    reader.SetColorMode(false);
    reader.SetLayerMode(false);
    reader.SetPropsMode(false);
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
      result.status = Status::failure(StatusCode::ReadError, "cannot read STEP file");
      result.status.file = path;
      app->Close(doc);
      return result;
    }
    read_units(reader, result.assembly);
    if (progress && !progress->report("read", 0.3)) {
      result.status = Status::failure(StatusCode::Cancelled, "cancelled");
      app->Close(doc);
      return result;
    }
    if (!reader.Transfer(doc)) {
      result.status = Status::failure(StatusCode::ReadError, "STEP transfer failed");
      result.status.file = path;
      app->Close(doc);
      return result;
    }
    Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    TDF_LabelSequence roots;
    tool->GetFreeShapes(roots);
    StepTreeWalker walker(tool, result.assembly, progress);
    for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
      if (!walker.walk(roots.Value(i), TopLoc_Location(), "")) {
        result.status = Status::failure(StatusCode::Cancelled, "cancelled");
        break;
      }
    }
    app->Close(doc);
    make_names_unique(result.assembly.bodies);
    if (result.status.ok() && result.assembly.bodies.empty()) {
      result.status = Status::failure(StatusCode::InvalidInput, "no solid in the file");
      result.status.file = path;
    }
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::ReadError,
                                    std::string("OCCT: ") + failure.GetMessageString());
    result.status.file = path;
  }
  if (progress && result.status.ok()) progress->report("read", 1.0);
  return result;
}

Status shape_from_brep(const std::string& brep, TopoDS_Shape& shape) {
  try {
    std::istringstream stream(brep);
    BRep_Builder builder;
    BRepTools::Read(shape, stream, builder);
  } catch (const Standard_Failure& failure) {
    return Status::failure(StatusCode::InvalidInput,
                           std::string("unreadable BRep: ") + failure.GetMessageString());
  }
  if (shape.IsNull()) return Status::failure(StatusCode::InvalidInput, "unreadable BRep: no shape");
  return Status::success();
}

std::string shape_to_brep(const TopoDS_Shape& shape) {
  std::ostringstream stream;
  BRepTools::Write(shape, stream);
  return stream.str();
}

AssemblyResult bodies_from_brep(const std::string& brep, const std::vector<std::string>& names) {
  AssemblyResult result;
  TopoDS_Shape compound;
  result.status = shape_from_brep(brep, compound);
  if (!result.status.ok()) return result;
  try {
    std::vector<TopoDS_Shape> children;
    if (compound.ShapeType() == TopAbs_COMPOUND) {
      for (TopoDS_Iterator it(compound); it.More(); it.Next()) children.push_back(it.Value());
    } else {
      children.push_back(compound);
    }
    for (size_t i = 0; i < children.size(); ++i) {
      const std::string name = i < names.size() ? names[i] : "Body" + std::to_string(i + 1);
      const SolidHarvest harvest = harvest_solids(children[i]);
      if (harvest.solids.empty()) {
        result.assembly.messages.push_back(skipped_message(name, harvest));
        continue;
      }
      if (harvest.open_shells || harvest.loose_faces)
        result.assembly.messages.push_back(skipped_message(name, harvest));
      // One body per child: FreeCAD face names (FaceN) index the child's faces.
      result.assembly.bodies.push_back(Body{name, name, children[i]});
    }
    make_names_unique(result.assembly.bodies);
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::InvalidInput,
                                    std::string("OCCT: ") + failure.GetMessageString());
  }
  return result;
}

MassProperties mass_properties(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return {props.Mass(), props.CentreOfMass()};
}

const MassProperties& Body::mass() const {
  std::call_once(mass_cache->once, [this] { mass_cache->value = mass_properties(shape); });
  return mass_cache->value;
}

bool compute_mass_properties(const Assembly& assembly, int threads, Progress* progress) {
  const std::vector<Body>& bodies = assembly.bodies;
  const std::vector<int> sources = instance_sources(bodies);
  if (!parallel_for(bodies.size(), threads, progress, "mass properties", [&](std::size_t i) {
        if (sources[i] == static_cast<int>(i)) bodies[i].mass();
      }, 4))
    return false;
  return parallel_for(bodies.size(), threads, progress, "mass properties", [&](std::size_t i) {
    const int source = sources[i];
    if (source == static_cast<int>(i)) return;
    std::call_once(bodies[i].mass_cache->once, [&] {
      MassProperties moved = bodies[source].mass();  // a rigid motion keeps the volume
      moved.centre.Transform(relative_motion(bodies[source], bodies[i]));
      bodies[i].mass_cache->value = moved;
    });
  }, 64);
}

TopoDS_Shape assembly_compound(const Assembly& assembly) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const Body& body : assembly.bodies) builder.Add(compound, body.shape);
  return compound;
}

}  // namespace contactcore
