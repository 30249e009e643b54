#include "bodies/step_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <Interface_Check.hxx>
#include <Interface_EntityIterator.hxx>
#include <Interface_Graph.hxx>
#include <Interface_ReportEntity.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepData_UndefinedEntity.hxx>
#include <StepBasic_MeasureValueMember.hxx>
#include <StepBasic_MeasureWithUnit.hxx>
#include <StepGeom_CartesianPoint.hxx>
#include <StepGeom_Circle.hxx>
#include <StepGeom_ConicalSurface.hxx>
#include <StepGeom_CylindricalSurface.hxx>
#include <StepGeom_Direction.hxx>
#include <StepGeom_Ellipse.hxx>
#include <StepGeom_SphericalSurface.hxx>
#include <StepGeom_ToroidalSurface.hxx>
#include <StepGeom_Vector.hxx>
#include <StepRepr_MappedItem.hxx>
#include <StepRepr_Representation.hxx>
#include <StepRepr_RepresentationMap.hxx>
#include <StepShape_GeometricSet.hxx>
#include <StepRepr_AssemblyComponentUsage.hxx>
#include <TCollection_HAsciiString.hxx>

#include "contactcore/common/occt_guard.h"
#include "contactcore/common/parallel.h"

namespace contactcore {

namespace {

constexpr size_t kMaxDamagedListed = 5;

std::string entity_label(const Handle(StepData_StepModel)& model, const Handle(Standard_Transient)& entity) {
  return "#" + std::to_string(model->IdentLabel(entity));
}

void find_damaged(const Handle(StepData_StepModel)& model, StepModelCheck& out) {
  for (Standard_Integer num = 1; num <= model->NbEntities(); ++num) {
    const bool unknown = model->IsUnknownEntity(num);
    const bool error = model->IsErrorEntity(num);
    if (!unknown && !error) continue;
    ++out.damaged_count;
    if (out.damaged.size() >= kMaxDamagedListed) continue;
    const Handle(Standard_Transient) entity = model->Value(num);
    std::string text = entity_label(model, entity) + ": ";
    Handle(StepData_UndefinedEntity) undefined = Handle(StepData_UndefinedEntity)::DownCast(entity);
    if (undefined.IsNull()) {
      const Handle(Interface_ReportEntity) report = model->ReportEntity(num);
      if (!report.IsNull()) undefined = Handle(StepData_UndefinedEntity)::DownCast(report->Content());
    }
    if (unknown && !undefined.IsNull() && undefined->StepType()) {
      text += std::string("unknown entity type ") + undefined->StepType();
    } else {
      text += "unreadable entity";
      const Handle(Interface_ReportEntity) report = model->ReportEntity(num);
      if (!report.IsNull() && !report->Check().IsNull() && report->Check()->NbFails() > 0) {
        text += " (" + std::string(report->Check()->Fail(1)->ToCString()) + ")";
      }
    }
    out.damaged.push_back(text);
  }
}

// Beyond this a coordinate (mm or inch) is no model: products of two overflow.
constexpr double kMaxCoordinate = 1e100;

bool usable(double value) { return std::isfinite(value) && std::fabs(value) <= kMaxCoordinate; }

bool usable(const Handle(StepGeom_CartesianPoint)& point) {
  // (CoordinatesValue, not Coordinates(): OCCT 7.6 copies into an array that is out of range)
  const Standard_Integer n = point->NbCoordinates();
  if (n < 1 || n > 3) return false;
  for (Standard_Integer i = 1; i <= n; ++i)
    if (!usable(point->CoordinatesValue(i))) return false;
  return true;
}

bool usable(const Handle(StepGeom_Direction)& direction) {
  const Handle(TColStd_HArray1OfReal) ratios = direction->DirectionRatios();
  if (ratios.IsNull() || ratios->Length() < 1) return false;
  for (Standard_Integer i = ratios->Lower(); i <= ratios->Upper(); ++i)
    if (!usable(ratios->Value(i))) return false;
  return true;
}

bool coordinates_unreadable(const Handle(StepData_StepModel)& model, Standard_Integer num) {
  if (!model->IsErrorEntity(num)) return false;
  const Handle(Interface_ReportEntity) report = model->ReportEntity(num);
  if (report.IsNull() || report->Check().IsNull()) return true;
  const Handle(Interface_Check) check = report->Check();
  for (Standard_Integer i = 1; i <= check->NbFails(); ++i) {
    const std::string fail = check->Fail(i)->ToCString();
    if (fail.find("coordinates") != std::string::npos || fail.find("direction_ratios") != std::string::npos)
      return true;
  }
  return false;
}

// The numbers of the other entities whose one number sizes a shape or a
// unit (issue 25: VECTOR('',#116,1.E+400) and a length unit of infinite
// factor made OCCT's transfer run for minutes): a type name for the message
// when one is not usable, else nullptr.
const char* unusable_measure(const Handle(Standard_Transient)& entity) {
  if (const auto vector = Handle(StepGeom_Vector)::DownCast(entity); !vector.IsNull())
    return usable(vector->Magnitude()) ? nullptr : "VECTOR";
  if (const auto circle = Handle(StepGeom_Circle)::DownCast(entity); !circle.IsNull())
    return usable(circle->Radius()) ? nullptr : "CIRCLE";
  if (const auto ellipse = Handle(StepGeom_Ellipse)::DownCast(entity); !ellipse.IsNull())
    return usable(ellipse->SemiAxis1()) && usable(ellipse->SemiAxis2()) ? nullptr : "ELLIPSE";
  if (const auto cylinder = Handle(StepGeom_CylindricalSurface)::DownCast(entity); !cylinder.IsNull())
    return usable(cylinder->Radius()) ? nullptr : "CYLINDRICAL_SURFACE";
  if (const auto cone = Handle(StepGeom_ConicalSurface)::DownCast(entity); !cone.IsNull())
    return usable(cone->Radius()) && usable(cone->SemiAngle()) ? nullptr : "CONICAL_SURFACE";
  if (const auto sphere = Handle(StepGeom_SphericalSurface)::DownCast(entity); !sphere.IsNull())
    return usable(sphere->Radius()) ? nullptr : "SPHERICAL_SURFACE";
  if (const auto torus = Handle(StepGeom_ToroidalSurface)::DownCast(entity); !torus.IsNull())
    return usable(torus->MajorRadius()) && usable(torus->MinorRadius()) ? nullptr : "TOROIDAL_SURFACE";
  if (const auto measure = Handle(StepBasic_MeasureWithUnit)::DownCast(entity); !measure.IsNull()) {
    if (measure->ValueComponentMember().IsNull()) return nullptr;
    const double value = measure->ValueComponent();
    // A unit's factor: finite, and neither zero nor beyond 1e100 either way.
    return std::isfinite(value) && std::fabs(value) <= kMaxCoordinate &&
                   (value == 0 || std::fabs(value) >= 1 / kMaxCoordinate)
               ? nullptr
               : "MEASURE_WITH_UNIT";
  }
  return nullptr;
}

void find_non_finite(const Handle(StepData_StepModel)& model, StepModelCheck& out) {
  for (Standard_Integer num = 1; num <= model->NbEntities(); ++num) {
    const Handle(Standard_Transient) entity = model->Value(num);
    const Handle(StepGeom_CartesianPoint) point = Handle(StepGeom_CartesianPoint)::DownCast(entity);
    const Handle(StepGeom_Direction) direction = Handle(StepGeom_Direction)::DownCast(entity);
    if (point.IsNull() && direction.IsNull()) {
      if (const char* type = unusable_measure(entity)) out.non_finite.push_back(entity_label(model, entity) + " (" + type + ")");
      continue;
    }
    // A coordinate that failed to read leaves whatever was there (an unset
    // name, "$" as some writers put, is harmless).
    const bool bad = coordinates_unreadable(model, num) || (point.IsNull() ? !usable(direction) : !usable(point));
    if (bad) out.non_finite.push_back(entity_label(model, entity) + (point.IsNull() ? " (DIRECTION)" : " (CARTESIAN_POINT)"));
  }
}

// Longest path and cycles in the graph "assembly product definition ->
// component product definition", iteratively (the tree can be very deep).
void check_assembly_graph(const Handle(StepData_StepModel)& model, StepModelCheck& out) {
  std::unordered_map<int, std::vector<int>> children;  // entity numbers
  for (Standard_Integer num = 1; num <= model->NbEntities(); ++num) {
    const Handle(StepRepr_AssemblyComponentUsage) usage =
        Handle(StepRepr_AssemblyComponentUsage)::DownCast(model->Value(num));
    if (usage.IsNull()) continue;
    const Handle(StepBasic_ProductDefinition) parent = usage->RelatingProductDefinition();
    const Handle(StepBasic_ProductDefinition) child = usage->RelatedProductDefinition();
    if (parent.IsNull() || child.IsNull()) continue;
    children[model->Number(parent)].push_back(model->Number(child));
  }
  if (children.empty()) return;
  enum Mark : char { Unseen = 0, Open, Done };
  std::unordered_map<int, char> mark;
  std::unordered_map<int, int> height;  // levels below a node, itself included
  std::unordered_map<int, double> instances;  // leaf instances below a node (1 for a leaf part)
  struct Frame {
    int node;
    size_t next;
  };
  for (const auto& entry : children) {
    if (mark[entry.first] != Unseen) continue;
    std::vector<Frame> stack{{entry.first, 0}};
    mark[entry.first] = Open;
    while (!stack.empty()) {
      Frame& frame = stack.back();
      const auto found = children.find(frame.node);
      const std::vector<int>* kids = found == children.end() ? nullptr : &found->second;
      if (kids && frame.next < kids->size()) {
        const int kid = (*kids)[frame.next++];
        if (mark[kid] == Open) {
          std::string cycle = entity_label(model, model->Value(kid));
          size_t start = stack.size();
          while (start > 0 && stack[start - 1].node != kid) --start;
          for (size_t i = start; i < stack.size(); ++i)
            cycle += " -> " + entity_label(model, model->Value(stack[i].node));
          out.cycle = cycle + " -> " + entity_label(model, model->Value(kid));
          return;
        }
        if (mark[kid] == Unseen) {
          mark[kid] = Open;
          stack.push_back({kid, 0});
        }
        continue;
      }
      int levels = 1;
      double below = kids ? 0 : 1;
      if (kids)
        for (int kid : *kids) {
          levels = std::max(levels, 1 + height[kid]);
          const auto leaf = instances.find(kid);
          below += leaf == instances.end() ? 1 : leaf->second;  // a kid with no kids: one part
        }
      height[frame.node] = levels;
      instances[frame.node] = below;
      mark[frame.node] = Done;
      out.assembly_depth = std::max(out.assembly_depth, levels);
      stack.pop_back();
    }
  }
  std::unordered_set<int> used;
  for (const auto& entry : children)
    for (int kid : entry.second) used.insert(kid);
  for (const auto& entry : children)
    if (!used.count(entry.first)) out.assembly_instances += instances[entry.first];
}

// Entities OCCT's transfer expands once per reference: sets of geometry and
// mapped items (with the representation map and representation they go through).
bool expands_per_reference(const Handle(Standard_Transient)& entity) {
  return entity->IsKind(STANDARD_TYPE(StepShape_GeometricSet)) || entity->IsKind(STANDARD_TYPE(StepRepr_MappedItem)) ||
         entity->IsKind(STANDARD_TYPE(StepRepr_RepresentationMap)) ||
         entity->IsKind(STANDARD_TYPE(StepRepr_Representation));
}

// Cycles and the longest chain of references between entities ("#10 refers to
// #11"), iteratively: OCCT's transfer follows references recursively, so a
// cycle (a MAPPED_ITEM whose map's representation holds it, an ORIENTED_EDGE of
// itself, a GEOMETRIC_SET in itself) overflows the stack, and a long chain
// (nested GEOMETRIC_SETs) takes time quadratic in its length before it does.
void check_reference_graph(const Handle(StepData_StepModel)& model, const Interface_Graph& graph,
                           StepModelCheck& out) {
  const Standard_Integer count = graph.Size();
  std::vector<std::vector<int>> refers(static_cast<size_t>(count) + 1);
  for (Standard_Integer num = 1; num <= count; ++num) {
    for (Interface_EntityIterator it = graph.Shareds(graph.Entity(num)); it.More(); it.Next()) {
      const Standard_Integer target = graph.EntityNumber(it.Value());
      if (target > 0) refers[num].push_back(target);
    }
  }
  enum Mark : char { Unseen = 0, Open, Done };
  std::vector<char> mark(refers.size(), Unseen);
  std::vector<int> height(refers.size(), 0);  // entities on the longest chain from here, itself included
  // Items a container expands to (expands_per_reference; 0 for other entities).
  std::vector<double> expansion(refers.size(), 0);
  std::vector<char> container(refers.size(), 0);
  for (Standard_Integer num = 1; num <= count; ++num) container[num] = expands_per_reference(graph.Entity(num));
  struct Frame {
    int node;
    size_t next;
  };
  std::vector<Frame> stack;
  for (int root = 1; root <= count; ++root) {
    if (mark[root] != Unseen) continue;
    stack.push_back({root, 0});
    mark[root] = Open;
    while (!stack.empty()) {
      Frame& frame = stack.back();
      const std::vector<int>& next = refers[frame.node];
      if (frame.next < next.size()) {
        const int target = next[frame.next++];
        if (mark[target] == Open) {
          size_t start = stack.size();
          while (start > 0 && stack[start - 1].node != target) --start;
          if (start > 0) --start;  // from the target itself
          std::string cycle;
          for (size_t i = start; i < stack.size(); ++i) cycle += entity_label(model, model->Value(stack[i].node)) + " -> ";
          out.reference_cycle = cycle + entity_label(model, model->Value(target));
          return;
        }
        if (mark[target] == Unseen) {
          mark[target] = Open;
          stack.push_back({target, 0});
        }
        continue;
      }
      int levels = 1;
      for (int target : next) levels = std::max(levels, 1 + height[target]);
      height[frame.node] = levels;
      mark[frame.node] = Done;
      if (container[frame.node]) {
        double items = 0;
        for (int target : next) items += container[target] ? expansion[target] : 1;
        expansion[frame.node] = items;
        if (items > out.largest_expansion) {
          out.largest_expansion = items;
          out.largest_container = entity_label(model, model->Value(frame.node));
        }
      }
      if (levels > out.reference_depth) {
        out.reference_depth = levels;
        out.deepest_entity = entity_label(model, model->Value(frame.node));
      }
      stack.pop_back();
    }
  }
}

}  // namespace

StepModelCheck check_step_model(const Handle(StepData_StepModel)& model, const Interface_Graph& graph) {
  StepModelCheck out;
  if (model.IsNull()) return out;
  // The per-entity checks only read the model: they run on a second thread
  // beside the walk of the reference graph (OCCT's graph, on this thread).
  // Should they fail there (an OCCT exception or signal on a damaged model),
  // they run again here, so the read reports the failure as before.
  StepModelCheck entities;
  const auto check_entities = [&model](StepModelCheck& into) {
    find_damaged(model, into);
    find_non_finite(model, into);
    check_assembly_graph(model, into);
  };
  bool failed = false;
  run_beside(
      [&] {
        std::string failure;
        failed = !run_guarded([&] { check_entities(entities); }, failure);
      },
      [&] { check_reference_graph(model, graph, out); });
  if (failed) {
    entities = StepModelCheck{};
    check_entities(entities);
  }
  out.damaged = std::move(entities.damaged);
  out.damaged_count = entities.damaged_count;
  out.non_finite = std::move(entities.non_finite);
  out.cycle = std::move(entities.cycle);
  out.assembly_depth = entities.assembly_depth;
  out.assembly_instances = entities.assembly_instances;
  return out;
}

DuplicateIdentifiers find_duplicate_identifiers(const std::string& path) {
  DuplicateIdentifiers out;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return out;
  // Identifiers are dense in practice (#1..#N): a bit each, a set beyond.
  constexpr unsigned long long kDenseLimit = 1ull << 28;
  std::vector<bool> dense;
  std::unordered_set<unsigned long long> sparse;
  const auto seen_before = [&](unsigned long long id) {
    if (id < kDenseLimit) {
      if (id >= dense.size()) dense.resize(std::max<size_t>(id + 1, dense.size() * 2));
      const bool seen = dense[id];
      dense[id] = true;
      return seen;
    }
    return !sparse.insert(id).second;
  };
  // A statement's start: "#<digits> =" there defines an entity; quoted
  // strings and /* comments */ are skipped. A string ends, as OCCT 7.6's
  // lexer (step.lex) ends it, only at a quote followed by blanks or line
  // ends and then ',' or ')': any other quote is part of it (a quote left
  // open by damaged text runs on, and definitions after it are text).
  enum class At { StatementStart, Hash, Number, AfterNumber, Body } at = At::StatementStart;
  bool in_string = false, in_comment = false;
  bool quote_in_string = false;  // in a string, a quote seen and only blanks since
  char previous = 0;
  unsigned long long id = 0;
  int digits = 0;
  long line = 1;
  std::vector<char> buffer(1 << 20);
  size_t got;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0) {
    for (size_t i = 0; i < got; ++i) {
      const char c = buffer[i];
      if (c == '\n') ++line;
      if (in_comment) {
        if (previous == '*' && c == '/') in_comment = false, previous = 0;
        else previous = c;
        continue;
      }
      if (in_string) {
        const bool blank = c == ' ' || c == '\n' || c == '\r';
        if (quote_in_string && (c == ',' || c == ')')) {
          in_string = quote_in_string = false;  // the string ended at that quote: `c` is outside
        } else {
          if (c == '\'') quote_in_string = true;
          else if (!blank) quote_in_string = false;
          previous = c;
          continue;
        }
      }
      if (previous == '/' && c == '*') {
        in_comment = true;
        previous = 0;
        continue;
      }
      previous = c;
      const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\n';
      if (c == '\'') {
        in_string = true;
        at = At::Body;
        continue;
      }
      if (c == ';') {
        at = At::StatementStart;
        continue;
      }
      switch (at) {
        case At::StatementStart:
          if (c == '#') at = At::Hash, id = 0, digits = 0;
          else if (!space && c != '/') at = At::Body;
          break;
        case At::Hash:
        case At::Number:
          if (c >= '0' && c <= '9') {
            if (++digits <= 18) id = id * 10 + static_cast<unsigned long long>(c - '0');
            at = At::Number;
          } else if (at == At::Number && (space || c == '=')) {
            at = At::AfterNumber;
          } else {
            at = At::Body;
          }
          if (at != At::AfterNumber || c != '=') break;
          [[fallthrough]];
        case At::AfterNumber:
          if (c == '=') {
            if (digits <= 18 && seen_before(id)) {
              if (out.listed.size() < kMaxDamagedListed)
                out.listed.push_back("#" + std::to_string(id) + " (again on line " + std::to_string(line) + ")");
              ++out.count;
            }
            at = At::Body;
          } else if (!space) {
            at = At::Body;
          }
          break;
        case At::Body:
          break;
      }
    }
  }
  return out;
}

std::string describe_duplicates(const DuplicateIdentifiers& duplicates) {
  std::string text;
  for (const std::string& item : duplicates.listed) text += (text.empty() ? "" : ", ") + item;
  const int more = duplicates.count - static_cast<int>(duplicates.listed.size());
  if (more > 0) text += " and " + std::to_string(more) + " more";
  return text;
}

std::string describe_damaged(const StepModelCheck& check) {
  std::string text;
  for (const std::string& item : check.damaged) text += (text.empty() ? "" : "; ") + item;
  const int more = check.damaged_count - static_cast<int>(check.damaged.size());
  if (more > 0) text += " and " + std::to_string(more) + " more";
  return text;
}

std::string describe_non_finite(const StepModelCheck& check) {
  std::string text;
  const size_t shown = std::min(check.non_finite.size(), kMaxDamagedListed);
  for (size_t i = 0; i < shown; ++i) text += (i ? ", " : "") + check.non_finite[i];
  if (check.non_finite.size() > shown) text += " and " + std::to_string(check.non_finite.size() - shown) + " more";
  return text;
}

}  // namespace contactcore
