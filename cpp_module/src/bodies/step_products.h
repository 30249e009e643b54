// Stage 1 (bodies): the STEP read that scales. OCCT's XDE read costs time
// quadratic in the parts: each occurrence's transfer scans every user of its
// product's representation (STEPConstruct_Assembly::CheckSRRReversesNAUO, the
// search of the product "really" placed) and every item of its parent's
// representation (ComputeTransformation), and XDE then looks labels up one by
// one. Here the product structure (PRODUCT_DEFINITION, NEXT_ASSEMBLY_USAGE_
// OCCURRENCE, CONTEXT_DEPENDENT_SHAPE_REPRESENTATION) is indexed once, each
// leaf product is transferred once by OCCT's own actor, and its instances are
// placed by the occurrences' transformations (computed as OCCT does, with the
// units of each representation): the same bodies, names, paths and
// placements as the XDE read, in the same order.
//
// A product whose shape is a compound of representations (a hybrid model: a
// solid beside a surface model; a representation mapping other products'
// with MAPPED_ITEMs) is read as XDE reads it: a sub-assembly of its parts.
// A file whose product structure holds something this path does not know
// (an assembly with geometry of its own, product definitions with documents,
// an occurrence without one placement, representations nested in such a
// compound) is left to the XDE read: plan_products and read_products say why.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <STEPCAFControl_Reader.hxx>
#include <TCollection_ExtendedString.hxx>

#include "contactcore/bodies/bodies.h"

namespace contactcore {

class ProductPlan;

// XDE's reader, its name conversion (STEP's \X2\ escapes, the file's code
// page) open to the fast path, so names come out exactly as XDE gives them.
class StepReader : public STEPCAFControl_Reader {
 public:
  TCollection_ExtendedString name_of(const TCollection_AsciiString& text) const { return convertName(text); }
};

struct ProductPlanResult {
  std::shared_ptr<ProductPlan> plan;  // null when the fast path cannot serve the file
  std::string why_not;                // then: what it met ("an assembly with geometry of its own: #12")
  bool needs_whole_text = false;      // a shortened list is not an assembly's: parse the file as written
};

// Inspects a parsed model (linear in its entities; nothing transferred yet).
// `shortened`: the placements taken out of SHAPE_REPRESENTATIONs' lists before
// parsing (step_placement_lists.h), per representation's #number; each must be
// an assembly's representation, whose items the read asks about only here.
ProductPlanResult plan_products(const StepReader& reader,
                                const std::unordered_map<int, std::vector<int>>* shortened = nullptr);

struct ProductRead {
  enum Outcome { Done, Cancelled, NotServed } outcome = Done;
  std::string why_not;  // NotServed: what the transfer showed (a product XDE would expand)
};

// Transfers each leaf product once and appends the placed solids to `out`
// (bodies in the XDE walk's order, names not yet made unique; skipped shells
// as messages). Reports "read" from `from` to `to`. NotServed (nothing
// appended) when a product's compound of representations holds another such
// compound (XDE would nest sub-assemblies): the caller reads the file through
// XDE then.
ProductRead read_products(const ProductPlan& plan, StepReader& reader, Assembly& out, Progress* progress,
                          double from, double to);

}  // namespace contactcore
