#include "bodies/step_products.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <Geom_Axis2Placement.hxx>
#include <Interface_Static.hxx>
#include <Message_ProgressScope.hxx>
#include <STEPControl_ActorRead.hxx>
#include <StepBasic_Product.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepBasic_ProductDefinitionFormation.hxx>
#include <StepBasic_ProductDefinitionWithAssociatedDocuments.hxx>
#include <StepData_StepModel.hxx>
#include <StepGeom_Axis2Placement3d.hxx>
#include <StepGeom_CartesianTransformationOperator3d.hxx>
#include <StepRepr_CharacterizedDefinition.hxx>
#include <StepRepr_HArray1OfRepresentationItem.hxx>
#include <StepRepr_ItemDefinedTransformation.hxx>
#include <StepRepr_NextAssemblyUsageOccurrence.hxx>
#include <StepRepr_ProductDefinitionShape.hxx>
#include <StepRepr_Representation.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepRepr_RepresentationRelationship.hxx>
#include <StepRepr_RepresentedDefinition.hxx>
#include <StepRepr_ShapeAspect.hxx>
#include <StepRepr_ShapeRepresentationRelationship.hxx>
#include <StepRepr_ShapeRepresentationRelationshipWithTransformation.hxx>
#include <StepRepr_Transformation.hxx>
#include <StepShape_ContextDependentShapeRepresentation.hxx>
#include <StepShape_ShapeDefinitionRepresentation.hxx>
#include <StepToGeom.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopAbs.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS_Iterator.hxx>
#include <StepShape_ShapeRepresentation.hxx>
#include <TransferBRep.hxx>
#include <Transfer_Binder.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <gp_Ax3.hxx>
#include <gp_Trsf.hxx>

#include "bodies/solid_harvest.h"
#include "common/occt_progress.h"

namespace contactcore {

namespace {

template <class T>
const void* key(const Handle(T)& handle) {
  return handle.get();
}

std::string entity_ref(const Handle(StepData_StepModel)& model, const Handle(Standard_Transient)& entity) {
  return "#" + std::to_string(model->IdentLabel(entity));
}

std::string utf8(const TCollection_ExtendedString& text) {
  std::string out(static_cast<size_t>(text.LengthOfCString()), '\0');
  Standard_PCharacter buffer = out.data();
  text.ToUTF8CString(buffer);
  out.resize(std::char_traits<char>::length(out.c_str()));
  return out;
}

// A name with some text: an ASCII graphic character or a byte of a UTF-8
// character (issue 25: XDE's UsefullLength counts ASCII only, so a name wholly
// in Cyrillic or emoji, decoded from \X2\ or \X4\, gave way to the id).
bool useful(const Handle(TCollection_HAsciiString)& text) {
  if (text.IsNull()) return false;
  for (Standard_Integer i = 1; i <= text->Length(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text->Value(i));
    if (c > 0x20 && c != 0x7f) return true;
  }
  return false;
}

}  // namespace

// One occurrence of a product in its parent (a NEXT_ASSEMBLY_USAGE_OCCURRENCE).
struct Occurrence {
  int child = 0;  // product index
  std::string name;
  Handle(StepRepr_RepresentationRelationship) relation;  // the placement (CDSR's relationship)
  bool reversed = false;  // the relationship names the parent's representation first
};

struct Product {
  Handle(StepBasic_ProductDefinition) definition;
  std::string name;
  std::vector<Occurrence> children;  // in the model's order, as OCCT builds the assembly
};

class ProductPlan {
 public:
  std::vector<Product> products;
  std::vector<int> roots;  // free products in the model's order
  // Per assembly representation whose list of placements was shortened before
  // parsing, the #numbers taken out of it (still its items for the placements).
  std::unordered_map<const void*, std::unordered_set<int>> removed_items;
};

ProductPlanResult plan_products(const StepReader& reader, const std::unordered_map<int, std::vector<int>>* shortened) {
  ProductPlanResult result;
  const Handle(StepData_StepModel) model = reader.Reader().StepModel();
  if (model.IsNull()) {
    result.why_not = "no parsed model";
    return result;
  }
  const auto fail = [&result](const std::string& why) {
    result.why_not = why;
    return result;
  };
  auto plan = std::make_shared<ProductPlan>();
  std::unordered_map<const void*, int> product_of;              // PRODUCT_DEFINITION -> index
  std::unordered_map<const void*, int> product_of_shape;        // PRODUCT_DEFINITION_SHAPE -> product
  std::unordered_map<const void*, const void*> occurrence_of_shape;  // PRODUCT_DEFINITION_SHAPE -> NAUO
  std::unordered_map<const void*, int> product_of_rep;          // SHAPE_REPRESENTATION -> product (its SDR)
  std::vector<Handle(StepRepr_NextAssemblyUsageOccurrence)> occurrences;
  std::vector<Handle(StepShape_ShapeDefinitionRepresentation)> definitions;
  std::vector<Handle(StepShape_ContextDependentShapeRepresentation)> placements;
  std::vector<Handle(StepRepr_ShapeAspect)> aspects;
  std::vector<Handle(StepRepr_RepresentationRelationship)> relations;
  const Handle(Standard_Type) nauo_type = STANDARD_TYPE(StepRepr_NextAssemblyUsageOccurrence);
  const Standard_Integer count = model->NbEntities();
  for (Standard_Integer i = 1; i <= count; ++i) {
    const Handle(Standard_Transient)& entity = model->Value(i);
    if (entity.IsNull()) continue;
    if (entity->IsKind(STANDARD_TYPE(StepBasic_ProductDefinitionWithAssociatedDocuments)))
      return fail("a product definition with documents (" + entity_ref(model, entity) + ")");
    if (entity->IsKind(STANDARD_TYPE(StepBasic_ProductDefinition))) {
      const auto definition = Handle(StepBasic_ProductDefinition)::DownCast(entity);
      Product product;
      product.definition = definition;
      // XDE's name for a product: its name, else its id (STEPCAFControl_Reader::ReadNames).
      const Handle(StepBasic_Product) of =
          definition->Formation().IsNull() ? Handle(StepBasic_Product)() : definition->Formation()->OfProduct();
      if (!of.IsNull()) {
        if (useful(of->Name())) product.name = utf8(reader.name_of(of->Name()->String()));
        else if (!of->Id().IsNull()) product.name = utf8(reader.name_of(of->Id()->String()));
      }
      product_of[key(definition)] = static_cast<int>(plan->products.size());
      plan->products.push_back(std::move(product));
    } else if (entity->IsKind(nauo_type)) {
      if (entity->DynamicType() != nauo_type) return fail("a subtype of an assembly occurrence (" + entity_ref(model, entity) + ")");
      occurrences.push_back(Handle(StepRepr_NextAssemblyUsageOccurrence)::DownCast(entity));
    } else if (entity->IsKind(STANDARD_TYPE(StepShape_ShapeDefinitionRepresentation))) {
      definitions.push_back(Handle(StepShape_ShapeDefinitionRepresentation)::DownCast(entity));
    } else if (entity->IsKind(STANDARD_TYPE(StepShape_ContextDependentShapeRepresentation))) {
      placements.push_back(Handle(StepShape_ContextDependentShapeRepresentation)::DownCast(entity));
    } else if (entity->IsKind(STANDARD_TYPE(StepRepr_ShapeAspect))) {
      aspects.push_back(Handle(StepRepr_ShapeAspect)::DownCast(entity));
    } else if (entity->IsKind(STANDARD_TYPE(StepRepr_RepresentationRelationship))) {
      relations.push_back(Handle(StepRepr_RepresentationRelationship)::DownCast(entity));
    }
  }
  if (plan->products.empty()) return fail("no product definition");
  // Product shapes (PRODUCT_DEFINITION_SHAPE of a PRODUCT_DEFINITION) and
  // occurrence shapes (of a NEXT_ASSEMBLY_USAGE_OCCURRENCE), by their users.
  std::unordered_map<const void*, int> occurrence_index;
  for (std::size_t k = 0; k < occurrences.size(); ++k) occurrence_index[key(occurrences[k])] = static_cast<int>(k);
  for (Standard_Integer i = 1; i <= count; ++i) {
    const auto shape = Handle(StepRepr_ProductDefinitionShape)::DownCast(model->Value(i));
    if (shape.IsNull()) continue;
    const StepRepr_CharacterizedDefinition definition = shape->Definition();
    const Handle(StepBasic_ProductDefinition) product = definition.ProductDefinition();
    if (!product.IsNull()) {
      const auto found = product_of.find(key(product));
      if (found != product_of.end()) product_of_shape[key(shape)] = found->second;
      continue;
    }
    const Handle(StepBasic_ProductDefinitionRelationship) relation = definition.ProductDefinitionRelationship();
    if (!relation.IsNull() && occurrence_index.count(key(relation))) occurrence_of_shape[key(shape)] = key(relation);
  }
  std::vector<std::vector<Handle(StepRepr_Representation)>> reps_of(plan->products.size());
  for (const auto& sdr : definitions) {
    const Handle(StepRepr_PropertyDefinition) property = sdr->Definition().PropertyDefinition();
    const auto found = property.IsNull() ? product_of_shape.end() : product_of_shape.find(key(property));
    if (found == product_of_shape.end()) continue;  // the shape of something else (an aspect)
    const Handle(StepRepr_Representation) rep = sdr->UsedRepresentation();
    if (rep.IsNull()) continue;
    if (product_of_rep.count(key(rep)) && product_of_rep[key(rep)] != found->second)
      return fail("one representation for two products (" + entity_ref(model, rep) + ")");
    product_of_rep[key(rep)] = found->second;
    reps_of[found->second].push_back(rep);
  }
  // Placements: one CDSR per occurrence.
  std::unordered_map<const void*, Handle(StepShape_ContextDependentShapeRepresentation)> placement_of;
  for (const auto& cdsr : placements) {
    const Handle(StepRepr_ProductDefinitionShape) shape = cdsr->RepresentedProductRelation();
    const auto found = shape.IsNull() ? occurrence_of_shape.end() : occurrence_of_shape.find(key(shape));
    if (found == occurrence_of_shape.end()) return fail("a placement of no assembly occurrence (" + entity_ref(model, cdsr) + ")");
    if (!placement_of.emplace(found->second, cdsr).second)
      return fail("an assembly occurrence placed twice (" + entity_ref(model, cdsr) + ")");
  }
  std::vector<char> is_child(plan->products.size(), 0);
  for (const auto& nauo : occurrences) {
    const auto parent = product_of.find(key(nauo->RelatingProductDefinition()));
    const auto child = product_of.find(key(nauo->RelatedProductDefinition()));
    if (parent == product_of.end() || child == product_of.end())
      return fail("an assembly occurrence of an unknown product (" + entity_ref(model, nauo) + ")");
    const auto placement = placement_of.find(key(nauo));
    if (placement == placement_of.end()) return fail("an assembly occurrence without a placement (" + entity_ref(model, nauo) + ")");
    Occurrence occurrence;
    occurrence.child = child->second;
    occurrence.relation = placement->second->RepresentationRelation();
    if (occurrence.relation.IsNull()) return fail("an assembly occurrence without a placement (" + entity_ref(model, nauo) + ")");
    // Which end of the relationship is the child's (as CheckSRRReversesNAUO decides, by the
    // products the two representations define, without scanning their users).
    const auto end_product = [&](const Handle(StepRepr_Representation)& rep) {
      const auto found = rep.IsNull() ? product_of_rep.end() : product_of_rep.find(key(rep));
      return found == product_of_rep.end() ? -1 : found->second;
    };
    const int p1 = end_product(occurrence.relation->Rep1()), p2 = end_product(occurrence.relation->Rep2());
    if (p1 == child->second && p2 == parent->second) occurrence.reversed = false;
    else if (p2 == child->second && p1 == parent->second) occurrence.reversed = true;
    else return fail("a placement whose representations are not its occurrence's products (" + entity_ref(model, nauo) + ")");
    // XDE's name for an occurrence: its description, else its name (else its product's, below).
    if (nauo->HasDescription() && useful(nauo->Description())) occurrence.name = utf8(reader.name_of(nauo->Description()->String()));
    else if (useful(nauo->Name())) occurrence.name = utf8(reader.name_of(nauo->Name()->String()));
    // no description nor name: the product's name is used below (issue 25: not the id)
    is_child[child->second] = 1;
    plan->products[parent->second].children.push_back(std::move(occurrence));
  }
  // An assembly's own representations may only hold placements: geometry of
  // its own, or representations related to them, XDE keeps beside the components.
  std::unordered_set<const void*> assembly_reps;
  for (std::size_t p = 0; p < plan->products.size(); ++p) {
    if (plan->products[p].children.empty()) continue;
    for (const auto& rep : reps_of[p]) {
      assembly_reps.insert(key(rep));
      const Handle(StepRepr_HArray1OfRepresentationItem) items = rep->Items();
      if (items.IsNull()) continue;
      for (Standard_Integer i = items->Lower(); i <= items->Upper(); ++i) {
        const Handle(StepRepr_RepresentationItem)& item = items->Value(i);
        if (!item.IsNull() && !item->IsKind(STANDARD_TYPE(StepGeom_Axis2Placement3d)))
          return fail("an assembly with geometry of its own (" + entity_ref(model, item) + " in " + entity_ref(model, rep) + ")");
      }
    }
  }
  // Shortened lists: only assemblies' (the transfer of a leaf, a root's
  // placement included, reads its representation's items).
  if (shortened && !shortened->empty()) {
    std::size_t matched = 0;
    for (std::size_t p = 0; p < plan->products.size(); ++p) {
      if (plan->products[p].children.empty()) continue;
      for (const auto& rep : reps_of[p]) {
        const auto found = shortened->find(model->IdentLabel(rep));
        if (found == shortened->end()) continue;
        auto& removed = plan->removed_items[key(rep)];
        if (removed.empty()) ++matched;
        removed.insert(found->second.begin(), found->second.end());
      }
    }
    if (matched != shortened->size()) {
      result.needs_whole_text = true;
      return fail("a shortened list of placements outside an assembly's representation");
    }
  }
  std::unordered_set<const void*> placement_relations;
  for (const auto& cdsr : placements) placement_relations.insert(key(cdsr->RepresentationRelation()));
  // A leaf product made of several representations (a hybrid model: a
  // solid beside a surface model) or whose representation maps other
  // products' (MAPPED_ITEM) transfers to a compound of representations, which
  // XDE makes a sub-assembly: read_products does as XDE does with it.
  for (const auto& relation : relations) {
    if (placement_relations.count(key(relation))) continue;
    if (assembly_reps.count(key(relation->Rep1())) || assembly_reps.count(key(relation->Rep2())))
      return fail("an assembly's representation related to another (" + entity_ref(model, relation) + ")");
  }
  for (const auto& aspect : aspects) {
    const auto found = aspect->OfShape().IsNull() ? product_of_shape.end() : product_of_shape.find(key(aspect->OfShape()));
    if (found != product_of_shape.end() && !plan->products[found->second].children.empty())
      return fail("a shape aspect of an assembly (" + entity_ref(model, aspect) + ")");
  }
  for (std::size_t p = 0; p < plan->products.size(); ++p)
    if (!is_child[p]) plan->roots.push_back(static_cast<int>(p));
  if (plan->roots.empty()) return fail("no free product");
  result.plan = std::move(plan);
  return result;
}

namespace {

// The placement of one occurrence, as STEPControl_ActorRead::ComputeSRRWT
// computes it, without its scan of both representations' items per call:
// the items are looked up in sets made once per representation.
class PlacementMaker {
 public:
  PlacementMaker(const Handle(STEPControl_ActorRead)& actor, const Handle(Transfer_TransientProcess)& process,
                 const ProductPlan& plan, const Handle(StepData_StepModel)& model)
      : actor_(actor), process_(process), plan_(plan), model_(model) {}

  gp_Trsf placement(const Handle(StepRepr_RepresentationRelationship)& relation) {
    const auto with_transformation = Handle(StepRepr_ShapeRepresentationRelationshipWithTransformation)::DownCast(relation);
    if (with_transformation.IsNull()) return gp_Trsf();
    const StepRepr_Transformation operation = with_transformation->TransformationOperator();
    if (!Handle(StepGeom_CartesianTransformationOperator3d)::DownCast(operation.Value()).IsNull()) {
      gp_Trsf trsf;  // rare: OCCT's own code (no scan of items there)
      actor_->ComputeSRRWT(relation, process_, trsf);
      current_.Nullify();
      return trsf;
    }
    const Handle(StepRepr_ItemDefinedTransformation) defined = operation.ItemDefinedTransformation();
    if (defined.IsNull()) return gp_Trsf();
    Handle(StepGeom_Axis2Placement3d) origin = Handle(StepGeom_Axis2Placement3d)::DownCast(defined->TransformItem1());
    Handle(StepGeom_Axis2Placement3d) target = Handle(StepGeom_Axis2Placement3d)::DownCast(defined->TransformItem2());
    if (origin.IsNull() || target.IsNull()) return gp_Trsf();
    const Handle(StepRepr_Representation) origin_rep = relation->Rep1(), target_rep = relation->Rep2();
    // Placements written the wrong way round (each in the other's representation) are swapped back.
    const bool origin_ok = holds(origin_rep, origin), target_ok = holds(target_rep, target);
    if ((!origin_ok || !target_ok) && holds(target_rep, origin) && holds(origin_rep, target)) std::swap(origin, target);
    units(origin_rep);
    const Handle(Geom_Axis2Placement) from = StepToGeom::MakeAxis2Placement(origin);
    units(target_rep);
    const Handle(Geom_Axis2Placement) to = StepToGeom::MakeAxis2Placement(target);
    gp_Trsf trsf;
    if (from.IsNull() || to.IsNull()) return trsf;
    trsf.SetTransformation(gp_Ax3(to->Ax2()), gp_Ax3(from->Ax2()));
    return trsf;
  }

 private:
  bool holds(const Handle(StepRepr_Representation)& rep, const Handle(StepGeom_Axis2Placement3d)& item) {
    if (rep.IsNull()) return false;
    auto found = items_.find(key(rep));
    if (found == items_.end()) {
      std::unordered_set<const void*> set;
      const Handle(StepRepr_HArray1OfRepresentationItem) items = rep->Items();
      if (!items.IsNull())
        for (Standard_Integer i = items->Lower(); i <= items->Upper(); ++i) set.insert(key(items->Value(i)));
      found = items_.emplace(key(rep), std::move(set)).first;
    }
    if (found->second.count(key(item))) return true;
    // An item taken out of the list before parsing (step_placement_lists.h).
    const auto removed = plan_.removed_items.find(key(rep));
    return removed != plan_.removed_items.end() && !model_.IsNull() && removed->second.count(model_->IdentLabel(item));
  }
  // The unit factors of `rep`'s context (PrepareUnits sets them globally for StepToGeom).
  void units(const Handle(StepRepr_Representation)& rep) {
    if (!current_.IsNull() && current_ == rep) return;
    actor_->PrepareUnits(rep, process_);
    current_ = rep;
  }
  Handle(STEPControl_ActorRead) actor_;
  Handle(Transfer_TransientProcess) process_;
  const ProductPlan& plan_;
  Handle(StepData_StepModel) model_;
  Handle(StepRepr_Representation) current_;
  std::unordered_map<const void*, std::unordered_set<const void*>> items_;
};

bool finite(const gp_Trsf& trsf) {
  for (int r = 1; r <= 3; ++r)
    for (int c = 1; c <= 4; ++c)
      if (!std::isfinite(trsf.Value(r, c))) return false;
  return true;
}

// Restores a static parameter on leaving (the transfer of a child product
// must not take its representation's placement as a root's).
class StaticIntegerScope {
 public:
  StaticIntegerScope(const char* name, int value) : name_(name), old_(Interface_Static::IVal(name)) {
    Interface_Static::SetIVal(name, value);
  }
  ~StaticIntegerScope() { Interface_Static::SetIVal(name_, old_); }

 private:
  const char* name_;
  int old_;
};

}  // namespace

ProductRead read_products(const ProductPlan& plan, StepReader& reader, Assembly& out, Progress* progress,
                          double from, double to) {
  ProductRead outcome;
  const auto cancelled = [&outcome] {
    outcome.outcome = ProductRead::Cancelled;
    return outcome;
  };
  STEPControl_Reader& step = reader.ChangeReader();
  const Handle(XSControl_TransferReader)& transfer = step.WS()->TransferReader();
  transfer->BeginTransfer();
  const Handle(Transfer_TransientProcess)& process = transfer->TransientProcess();
  const Handle(STEPControl_ActorRead) actor = Handle(STEPControl_ActorRead)::DownCast(transfer->Actor());
  if (process.IsNull() || actor.IsNull()) return outcome;  // nothing transferable: no bodies

  // Which products are placed (leaves of the tree from the roots) and which are roots.
  const std::size_t n = plan.products.size();
  std::vector<char> is_root(n, 0), is_leaf_used(n, 0), seen(n, 0);
  std::vector<int> stack(plan.roots.begin(), plan.roots.end());
  for (int root : plan.roots) is_root[root] = 1;
  std::vector<int> leaves;
  while (!stack.empty()) {
    const int p = stack.back();
    stack.pop_back();
    if (seen[p]) continue;
    seen[p] = 1;
    if (plan.products[p].children.empty()) {
      leaves.push_back(p);
      continue;
    }
    for (const Occurrence& child : plan.products[p].children) stack.push_back(child.child);
  }
  std::sort(leaves.begin(), leaves.end());  // the model's order

  // Each leaf product transferred once, by OCCT's actor (units, shape
  // healing, mapped items and related representations as the XDE read has them).
  detail::CancelWatch watch(progress, "read");
  Handle(detail::OcctBreak) indicator = new detail::OcctBreak(watch, from, from + 0.9 * (to - from));
  Message_ProgressScope scope(indicator->Start(), "products", static_cast<Standard_Real>(std::max<std::size_t>(1, leaves.size())));
  // One part of a product XDE makes a sub-assembly (below).
  struct Component {
    std::string name;
    TopLoc_Location location;  // in the product
    SolidHarvest harvest;
    bool finite = true;
  };
  struct LeafShape {
    SolidHarvest harvest;
    bool finite = true;
    std::vector<Component> components;  // not empty: XDE's sub-assembly, placed instead of the solids
  };
  std::vector<LeafShape> shapes(n);
  for (int p : leaves) {
    const Handle(StepBasic_ProductDefinition)& definition = plan.products[p].definition;
    {
      // As OCCT transfers a child product through its occurrence: without the root's placement.
      const StaticIntegerScope root_placement("read.step.root.transformation",
                                              is_root[p] ? Interface_Static::IVal("read.step.root.transformation") : 0);
      transfer->TransferOne(definition, Standard_False, scope.Next());
    }
    if (watch.cancelled()) return cancelled();
    const TopoDS_Shape shape = TransferBRep::ShapeResult(process, process->Find(definition));
    if (shape.IsNull()) continue;
    LeafShape& leaf = shapes[p];
    leaf.harvest = harvest_solids(shape);
    leaf.finite = has_finite_box(shape);
  }

  // XDE makes a product whose shape is a compound holding results of
  // representations or of products (a hybrid model: a solid's representation
  // beside a surface model's; a representation mapping other products' with
  // MAPPED_ITEMs) a sub-assembly (STEPCAFControl_Reader::AddShape): each
  // element of the compound a component, placed by its location, named by
  // the product whose shape it is (ReadNames), else by its shape type
  // (XCAFDoc_ShapeTool's automatic names: "SOLID", "SHELL", "COMPOUND").
  // Such components are not free: a root product that is one is placed only
  // there (XDE's GetFreeShapes). Deeper nesting is left to XDE.
  TopTools_MapOfShape component_shapes;
  {
    TopTools_MapOfShape made;  // XDE's NewShapesMap: results of shape representations and products
    TopTools_DataMapOfShapeInteger product_of_shape;
    const Handle(StepData_StepModel) model = step.StepModel();
    for (Standard_Integer i = 1, count = model->NbEntities(); i <= count; ++i) {
      const Handle(Standard_Transient)& entity = model->Value(i);
      if (entity.IsNull() || !entity->IsKind(STANDARD_TYPE(StepShape_ShapeRepresentation))) continue;
      const Standard_Integer index = process->MapIndex(entity);
      if (index <= 0) continue;
      const TopoDS_Shape shape = TransferBRep::ShapeResult(process->MapItem(index));
      if (!shape.IsNull()) made.Add(shape);
    }
    for (int p : leaves) {
      const TopoDS_Shape shape = TransferBRep::ShapeResult(process, process->Find(plan.products[p].definition));
      if (shape.IsNull()) continue;
      made.Add(shape);
      if (!product_of_shape.IsBound(shape)) product_of_shape.Bind(shape, p);
    }
    const auto holds_made = [&made](const TopoDS_Shape& shape) {
      if (shape.ShapeType() != TopAbs_COMPOUND) return false;
      for (TopoDS_Iterator it(shape); it.More(); it.Next())
        if (made.Contains(it.Value().Located(TopLoc_Location()))) return true;
      return false;
    };
    for (int p : leaves) {
      const TopoDS_Shape shape = TransferBRep::ShapeResult(process, process->Find(plan.products[p].definition));
      if (shape.IsNull() || !holds_made(shape)) continue;
      LeafShape& leaf = shapes[p];
      for (TopoDS_Iterator it(shape); it.More(); it.Next()) {
        const TopoDS_Shape part = it.Value().Located(TopLoc_Location());
        if (holds_made(part)) {
          outcome.outcome = ProductRead::NotServed;
          outcome.why_not = "a product made of representations made of representations (" +
                            entity_ref(model, plan.products[p].definition) + ")";
          return outcome;
        }
        Component component;
        if (product_of_shape.IsBound(part)) component.name = plan.products[product_of_shape.Find(part)].name;
        else component.name = TopAbs::ShapeTypeToString(part.ShapeType());
        if (component.name.empty()) component.name = "Body";
        component.location = it.Value().Location();
        component.harvest = harvest_solids(part);
        component.finite = has_finite_box(part);
        leaf.components.push_back(std::move(component));
        component_shapes.Add(part);
      }
    }
  }

  // The tree walked as the XDE walk goes: roots in order, occurrences in order.
  PlacementMaker placements(actor, process, plan, step.StepModel());
  std::unordered_map<const void*, gp_Trsf> placement_cache;  // one relationship may place several (never in practice)
  std::size_t placed = 0;
  struct Frame {
    int product;
    TopLoc_Location location;
    std::string name, path;
  };
  std::vector<Frame> pending;
  for (auto it = plan.roots.rbegin(); it != plan.roots.rend(); ++it) {
    if (plan.products[*it].children.empty()) {
      const TopoDS_Shape shape = TransferBRep::ShapeResult(process, process->Find(plan.products[*it].definition));
      if (!shape.IsNull() && component_shapes.Contains(shape)) continue;  // a component of another root
    }
    std::string name = plan.products[*it].name.empty() ? "Body" : plan.products[*it].name;
    pending.push_back({*it, TopLoc_Location(), name, name});
  }
  while (!pending.empty()) {
    Frame frame = std::move(pending.back());
    pending.pop_back();
    const Product& product = plan.products[frame.product];
    if (product.children.empty()) {
      const LeafShape& leaf = shapes[frame.product];
      const auto place = [&out](const SolidHarvest& harvest, bool finite_shape, const TopLoc_Location& location,
                                const std::string& name, const std::string& path) {
        if (harvest.open_shells || harvest.loose_faces) out.messages.push_back(skipped_message(path, harvest));
        for (const TopoDS_Shape& solid : harvest.solids) {
          if (finite_shape && finite(location.Transformation()))
            out.bodies.push_back(Body{name, path, solid.Moved(location)});
          else
            out.messages.push_back("skipped '" + path + "': coordinates that are not finite numbers");
        }
      };
      if (leaf.components.empty()) place(leaf.harvest, leaf.finite, frame.location, frame.name, frame.path);
      for (const Component& component : leaf.components)
        place(component.harvest, component.finite, frame.location * component.location, component.name,
              frame.path + "/" + component.name);
      if (++placed % 1024 == 0 && !watch.report("read", from + 0.95 * (to - from))) return cancelled();
      continue;
    }
    for (auto it = product.children.rbegin(); it != product.children.rend(); ++it) {
      const Occurrence& occurrence = *it;
      auto cached = placement_cache.find(key(occurrence.relation));
      if (cached == placement_cache.end())
        cached = placement_cache.emplace(key(occurrence.relation), placements.placement(occurrence.relation)).first;
      const gp_Trsf& trsf = cached->second;
      const TopLoc_Location local = trsf.Form() == gp_Identity ? TopLoc_Location()
                                                                : TopLoc_Location(occurrence.reversed ? trsf.Inverted() : trsf);
      std::string name = occurrence.name;
      if (name.empty()) name = plan.products[occurrence.child].name;
      if (name.empty()) name = "Body";
      pending.push_back({occurrence.child, frame.location * local, name, frame.path + "/" + name});
    }
  }
  return outcome;
}

}  // namespace contactcore
