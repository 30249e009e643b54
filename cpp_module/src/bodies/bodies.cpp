#include "contactcore/bodies/bodies.h"
#include "contactcore/bodies/assembly_of_bodies.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/common/out_of_memory.h"
#include "bodies/step_check.h"
#include "bodies/solid_harvest.h"
#include "bodies/collapsed_seams.h"
#include "bodies/open_wires.h"
#include "bodies/step_products.h"
#include "bodies/step_placement_lists.h"
#include "bodies/step_scanner_input.h"

#include "contactcore/bodies/instances.h"
#include "contactcore/common/parallel.h"
#include "common/occt_progress.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#ifdef __GLIBC__
#include <malloc.h>  // malloc_trim
#endif
#include <sys/mman.h>  // the memory probe of parse_failure

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <Bnd_Box.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <XSControl_WorkSession.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_CString.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <StepBasic_Product.hxx>
#include <StepRepr_NextAssemblyUsageOccurrence.hxx>
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

// The file's own names where OCCT's reader put others (issue 25): an
// occurrence named '' or '$' gets its id ("2") from OCCT, one named wholly
// outside ASCII (\X2\ or \X4\ encoded: Cyrillic, emoji) too, and so does
// a product named so: OCCT's name (the id) -> the file's name in UTF-8 (empty:
// the occurrence takes its product's name).
struct StepNames {
  std::unordered_map<std::string, std::string> occurrence, product;
};

class StepTreeWalker {
 public:
  // `names`: the names OCCT put in place of the file's (step_names below).
  StepTreeWalker(Handle(XCAFDoc_ShapeTool) tool, Assembly& out, Progress* progress, StepNames names = {})
      : tool_(std::move(tool)), out_(out), progress_(progress), names_(std::move(names)) {}

  // `instance_name`: the name of the occurrence placing this shape (STEP's
  // NEXT_ASSEMBLY_USAGE_OCCURRENCE), which tells apart the instances of one
  // product; the product's own name otherwise.
  bool walk(const TDF_Label& label, const TopLoc_Location& location, const std::string& parent_path,
            const std::string& instance_name = {}) {
    // OCCT's transfer reported 0.3 to 0.9: the walk is the rest of the read.
    if (progress_ && !progress_->report("read", 0.9)) return false;
    std::string name = instance_name;
    if (name.empty()) {
      name = label_name(label);
      const auto named = names_.product.find(name);
      if (named != names_.product.end()) name = named->second;
    }
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
        const auto named = names_.occurrence.find(instance);
        if (named != names_.occurrence.end()) instance = named->second;  // empty: the product's name
        if (!walk(referred, placed, path, instance)) return false;
      }
      return true;
    }
    const TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
    if (shape.IsNull()) return true;
    const SolidHarvest harvest = harvest_solids(shape);
    if (harvest.open_shells || harvest.loose_faces) out_.messages.push_back(skipped_message(path, harvest));
    for (const TopoDS_Shape& solid : harvest.solids) {
      const TopoDS_Shape placed = solid.Moved(location);
      if (has_finite_box(placed))
        out_.bodies.push_back(Body{name, path, placed});
      else
        out_.messages.push_back("skipped '" + path + "': coordinates that are not finite numbers");
    }
    return true;
  }

 private:
  Handle(XCAFDoc_ShapeTool) tool_;
  Assembly& out_;
  Progress* progress_;
  StepNames names_;
};

// True when OCCT's reader takes this name for none: UsefullLength counts up
// to the last ASCII graphic character, so a name wholly outside ASCII (decoded
// from \X2\ or \X4\ to UTF-8) looks empty to it.
bool looks_empty_to_occt(const Handle(TCollection_HAsciiString)& text) {
  return text.IsNull() || text->UsefullLength() == 0;
}

bool has_graphic_text(const Handle(TCollection_HAsciiString)& text) {
  if (text.IsNull()) return false;
  for (const char c : std::string(text->ToCString()))
    if (static_cast<unsigned char>(c) > 0x20 && c != 0x7f) return true;  // ASCII graphic or a UTF-8 byte
  return false;
}

StepNames step_names(const Handle(StepData_StepModel)& model) {
  StepNames names;
  if (model.IsNull()) return names;
  for (Standard_Integer num = 1; num <= model->NbEntities(); ++num) {
    const Handle(Standard_Transient) entity = model->Value(num);
    if (const auto usage = Handle(StepRepr_NextAssemblyUsageOccurrence)::DownCast(entity); !usage.IsNull()) {
      // OCCT names an occurrence by its description, else its name, else its id.
      if (usage->Id().IsNull() || (usage->HasDescription() && !looks_empty_to_occt(usage->Description()))) continue;
      if (!looks_empty_to_occt(usage->Name())) continue;
      names.occurrence[usage->Id()->ToCString()] = has_graphic_text(usage->Name()) ? usage->Name()->ToCString() : "";
    } else if (const auto product = Handle(StepBasic_Product)::DownCast(entity); !product.IsNull()) {
      // A product by its name, else its id.
      if (product->Id().IsNull() || !looks_empty_to_occt(product->Name()) || !has_graphic_text(product->Name()))
        continue;
      names.product[product->Id()->ToCString()] = product->Name()->ToCString();
    }
  }
  return names;
}

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

namespace {

// Why a file cannot be read, said before OCCT tries (it says only "cannot read").
Status check_input_file(const std::string& path, const char* format) {
  const auto fail = [&path](StatusCode code, const std::string& message) {
    Status status = Status::failure(code, message);
    status.file = path;
    return status;
  };
  if (path.find('\0') != std::string::npos)
    return fail(StatusCode::InvalidInput, "the path contains a NUL character");
  if (path.empty()) return fail(StatusCode::InvalidInput, "empty path");
  std::error_code error;
  const std::filesystem::file_status info = std::filesystem::status(path, error);
  if (!std::filesystem::exists(info)) return fail(StatusCode::ReadError, "no such file");
  if (std::filesystem::is_directory(info)) return fail(StatusCode::ReadError, "a directory, not a file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) {
    const int code = errno;
    return fail(StatusCode::ReadError, code == EACCES ? std::string("permission denied")
                                                      : std::string("cannot open: ") + std::strerror(code));
  }
  char head[64] = {};
  probe.read(head, sizeof head);
  const std::string start(head, static_cast<size_t>(probe.gcount()));
  if (start.empty()) return fail(StatusCode::InvalidInput, "empty file");
  if (start.rfind("\x89PNG", 0) == 0) return fail(StatusCode::InvalidInput, std::string("not a ") + format + " file: a PNG image");
  if (start.rfind("PK\x03\x04", 0) == 0)
    return fail(StatusCode::InvalidInput, std::string("not a ") + format + " file: a zip archive (a FreeCAD document?)");
  if (std::string(format) == "STEP" && start.find("ISO-10303-21") == std::string::npos)
    return fail(StatusCode::InvalidInput, "not a STEP file: it does not begin with ISO-10303-21");
  return Status::success();
}

// BRep text OCCT's reader would loop on or misread (text cut short).
// OCCT 7.6 loops forever on an edge record cut short, so the text must hold
// its "TShapes N" table with N records (each ends with a '*' line) and the
// root reference after them.
Status check_brep_text(const std::string& brep) {
  const auto fail = [](const std::string& why) { return Status::failure(StatusCode::InvalidInput, "unreadable BRep: " + why); };
  if (brep.empty()) return fail("empty text");
  if (brep.find("CASCADE Topology") == std::string::npos) return fail("not BRep text (no 'CASCADE Topology' header)");
  const size_t table = brep.find("\nTShapes ");
  if (table == std::string::npos) return fail("text cut short (no TShapes table)");
  size_t line_start = brep.find('\n', table + 1);
  long expected = 0;
  try {
    expected = std::stol(brep.substr(table + 9, line_start == std::string::npos ? std::string::npos : line_start - table - 9));
  } catch (const std::exception&) {
    return fail("bad TShapes count");
  }
  // OCCT reads a damaged number in the geometry sections as 0 and goes on:
  // Booleans on such a face then spin for minutes (make fuzz).
  static constexpr std::string_view sections[] = {
      "Locations", "Curve2ds", "Curves", "Polygon3D", "PolygonOnTriangulations", "Surfaces", "Triangulations"};
  const size_t geometry = brep.find("Locations");
  if (geometry == std::string::npos || geometry > table) return fail("no Locations section");
  bool in_locations = false;
  for (size_t pos = geometry; pos < table;) {
    const size_t start = brep.find_first_not_of(" \t\r\n", pos);
    if (start == std::string::npos || start >= table) break;
    const size_t end = std::min(brep.find_first_of(" \t\r\n", start), table);
    const std::string_view token(brep.data() + start, end - start);
    pos = end;
    if (std::find(std::begin(sections), std::end(sections), token) != std::end(sections)) {
      in_locations = token == "Locations";
      continue;
    }
    if (token == "p") continue;  // a polygon on triangulation's "has parameters" mark (a meshed shape)
    char* stop = nullptr;
    // As OCCT reads it, whatever the locale. NaN and inf in a placement are
    // numbers: the bodies' boxes catch them later, naming the body. In a
    // curve or surface (1e+3000 in a pcurve) they gave a face of infinite area.
    const double value = Strtod(brep.c_str() + start, &stop);
    if (stop != brep.c_str() + end || (!in_locations && !std::isfinite(value))) {
      const long line = 1 + std::count(brep.begin(), brep.begin() + static_cast<long>(start), '\n');
      return fail(std::string(stop != brep.c_str() + end ? "damaged number '" : "number out of range '") +
                  std::string(token.substr(0, 40)) + "' on line " + std::to_string(line));
    }
  }
  // In the shapes' records, tolerances and parameter ranges: one out of
  // range (6.1e+300283 in an edge's range) gave a face of area NaN (make fuzz).
  for (size_t pos = line_start; pos != std::string::npos && pos < brep.size();) {
    const size_t start = brep.find_first_not_of(" \t\r\n", pos);
    if (start == std::string::npos) break;
    const size_t end = std::min(brep.find_first_of(" \t\r\n", start), brep.size());
    pos = end;
    char* stop = nullptr;
    const double value = Strtod(brep.c_str() + start, &stop);
    if (stop == brep.c_str() + end && !std::isfinite(value)) {  // a whole number token (names and flags are not)
      const long line = 1 + std::count(brep.begin(), brep.begin() + static_cast<long>(start), '\n');
      return fail("number out of range '" + brep.substr(start, std::min<size_t>(end - start, 40)) + "' on line " +
                  std::to_string(line));
    }
  }
  long records = 0;
  while (line_start != std::string::npos && records < expected) {
    const size_t next = brep.find('\n', line_start + 1);
    size_t end = next == std::string::npos ? brep.size() : next;
    while (end > line_start + 1 && std::isspace(static_cast<unsigned char>(brep[end - 1]))) --end;
    if (end > line_start + 1 && brep[end - 1] == '*') ++records;
    line_start = next;
  }
  if (records < expected)
    return fail("text cut short (" + std::to_string(records) + " of " + std::to_string(expected) + " shapes)");
  if (line_start == std::string::npos || brep.find_first_not_of(" \t\r\n", line_start) == std::string::npos)
    return fail("text cut short (no root shape)");
  return Status::success();
}

// OCCT's console messages about the file, as notes ("StepFile : Incorrect Syntax ...").
void keep_reader_notes(const OcctGuard& guard, std::vector<std::string>& messages) {
  for (const std::string& line : guard.messages()) {
    std::string text = line;
    text.erase(0, text.find_first_not_of(" *\t"));
    while (!text.empty() && (text.back() == ' ' || text.back() == '*' || text.back() == '\n')) text.pop_back();
    if (!text.empty()) messages.push_back("STEP reader: " + text);
  }
}

// Why OCCT's STEP parser gave up on a file, as the read's status: out of
// memory or an unreadable file. OCCT's parser catches its own
// Standard_OutOfMemory and only says so, or fails without a word (a block it
// could not allocate, under `ulimit -v`): a silent failure is out of memory
// when 16 MB of address space cannot be had now. The probe is a mapping, not
// a malloc: clang removes a malloc whose block is only compared with null and
// freed (it may assume the allocation succeeds), and its build then called an
// out-of-memory parse an unreadable file (issue 23). Only the messages from
// `first_message` on are that parse's (a second read follows a first one).
Status parse_failure(const OcctGuard& guard, std::size_t first_message, const std::string& what) {
  std::string why;
  const std::vector<std::string> messages = guard.messages();
  for (std::size_t i = first_message; i < messages.size(); ++i) why += (why.empty() ? "" : "; ") + messages[i];
  const auto memory_left = [] {
    constexpr std::size_t probe_size = std::size_t(16) << 20;
    void* probe = mmap(nullptr, probe_size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (probe == MAP_FAILED) return false;
    munmap(probe, probe_size);
    return true;
  };
  if (why.find("Standard_OutOfMemory") != std::string::npos || why.find("malloc failed") != std::string::npos ||
      (why.empty() && !memory_left()))
    return Status::failure(StatusCode::OutOfMemory, "out of memory while reading the STEP file");
  return Status::failure(StatusCode::ReadError, what + (why.empty() ? std::string() : ": " + why));
}

// The read's error when OCCT's STEP transfer throws: the exception's type
// and message, and the file's damaged entities when the check found any.
std::string transfer_failure(const Standard_Failure& failure, const StepModelCheck& check) {
  std::string message = std::string("STEP transfer failed inside OCCT (") + failure.DynamicType()->Name();
  if (failure.GetMessageString() && *failure.GetMessageString()) message += ": " + std::string(failure.GetMessageString());
  message += ")";
  if (check.damaged_count) message += "; damaged entities: " + describe_damaged(check);
  return message;
}

}  // namespace

namespace {
// A stream over text in memory, not copied (OCCT's parser reads it once).
class TextBuffer : public std::streambuf {
 public:
  explicit TextBuffer(std::string& text) { setg(text.data(), text.data(), text.data() + text.size()); }
};
}  // namespace

AssemblyResult read_step(const std::string& path, Progress* progress, StepReadMode mode, std::size_t max_bodies) {
  AssemblyResult result;
  const auto fail = [&result, &path](StatusCode code, const std::string& message) {
    result.status = Status::failure(code, message);
    result.status.file = path;
    return result;
  };
  if (progress && !progress->report("read", 0.0)) return fail(StatusCode::Cancelled, "cancelled");
  result.status = check_input_file(path, "STEP");
  if (!result.status.ok()) return result;
  const DuplicateIdentifiers duplicates = find_duplicate_identifiers(path);
  if (duplicates.count)
    return fail(StatusCode::InvalidInput, "entities defined more than once: " + describe_duplicates(duplicates));
  // Damaged files make OCCT 7.6 dereference null handles: its signal handler
  // turns that into a Standard_Failure here, and its messages are kept off stdout.
  OcctGuard guard;
  Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) doc;
  try {
    OCC_CATCH_SIGNALS
    // Shapes come out in millimetres whatever the file's unit.
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    app->NewDocument("MDTV-XCAF", doc);
    StepReader reader;
    reader.SetNameMode(true);
    reader.SetColorMode(false);
    reader.SetLayerMode(false);
    reader.SetPropsMode(false);
    // The read by products parses the text with assemblies' lists of
    // placements shortened (step_placement_lists.h: OCCT's parser is
    // quadratic in a list's length); the XDE read parses the file as written.
    ShortenedPlacementLists shortened;
    IFSelect_ReturnStatus parsed;
    if (mode == StepReadMode::Products) {
      std::string text;
      {
        std::ifstream in(path, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
      shortened = shorten_placement_lists(text);
      if (shortened.changed()) std::string().swap(text);
      // OCCT's scanner fed in blocks, not a character per call (step_scanner_input.h).
      TextBuffer buffer(shortened.changed() ? shortened.text : text);
      std::istream stream(&buffer);
      {
        const detail::BlockReadScope blocks(buffer);
        parsed = reader.ChangeReader().ReadStream(path.c_str(), stream);
      }
      std::string().swap(shortened.text);  // parsed: the model holds it now
      std::string().swap(text);
    } else {
      parsed = reader.ReadFile(path.c_str());
    }
    if (parsed != IFSelect_RetDone) {
      const Status why = parse_failure(guard, 0, "not a readable STEP file");
      fail(why.code, why.message);
    } else {
      read_units(reader, result.assembly);
      const StepModelCheck check =
          check_step_model(reader.ChangeReader().StepModel(), reader.ChangeReader().WS()->Graph());
      if (!check.cycle.empty()) {
        fail(StatusCode::InvalidInput, "cyclic assembly reference (an assembly contains itself): " + check.cycle);
      } else if (check.assembly_depth > kMaxAssemblyDepth) {
        fail(StatusCode::InvalidInput, "assembly nested " + std::to_string(check.assembly_depth) +
                                           " levels deep (at most " + std::to_string(kMaxAssemblyDepth) + ")");
      } else if (!check.reference_cycle.empty()) {
        fail(StatusCode::InvalidInput, "cyclic reference (an entity refers to itself): " + check.reference_cycle);
      } else if (check.reference_depth > kMaxReferenceDepth) {
        fail(StatusCode::InvalidInput, "entities nested " + std::to_string(check.reference_depth) + " levels deep from " +
                                           check.deepest_entity + " (at most " + std::to_string(kMaxReferenceDepth) + ")");
      } else if (check.assembly_instances > static_cast<double>(max_bodies)) {
        char text[200];
        std::snprintf(text, sizeof text, "the assembly expands to %.6g instances: more than the limit of %zu bodies "
                                         "(CLI --max-bodies)", check.assembly_instances, max_bodies);
        fail(StatusCode::InvalidInput, text);
      } else if (check.largest_expansion > static_cast<double>(max_bodies)) {
        char text[200];
        std::snprintf(text, sizeof text, "%s expands to %.6g items through nested sets or mapped items: more than the "
                                         "limit of %zu (CLI --max-bodies)", check.largest_container.c_str(),
                      check.largest_expansion, max_bodies);
        fail(StatusCode::InvalidInput, text);
      } else if (!check.non_finite.empty()) {
        fail(StatusCode::InvalidInput, "coordinates that are not finite numbers (NaN, infinite or unreadable) in " +
                                           describe_non_finite(check));
      } else if (progress && !progress->report("read", 0.3)) {
        fail(StatusCode::Cancelled, "cancelled");
      } else {
        if (check.damaged_count)
          result.assembly.messages.push_back(std::to_string(check.damaged_count) +
                                             " damaged STEP entities ignored: " + describe_damaged(check));
        // The fast product read first; the XDE read when it cannot serve the
        // file, said where the user looks: the messages, and the progress (a
        // stage of its own).
        bool served = false;
        StepReader* xde_reader = &reader;
        std::unique_ptr<StepReader> reread;  // the products' transfer used the first reader's session
        const auto fall_back = [&](const std::string& why) {
          result.assembly.messages.push_back("STEP read: the fast product read cannot serve this file (" + why +
                                             "): read through OCCT's XDE reader");
          if (progress && !progress->report("read (XDE fallback)", 0.3)) fail(StatusCode::Cancelled, "cancelled");
        };
        const auto new_reader = [] {
          auto fresh = std::make_unique<StepReader>();
          fresh->SetNameMode(true);
          fresh->SetColorMode(false);
          fresh->SetLayerMode(false);
          fresh->SetPropsMode(false);
          return fresh;
        };
        // A second parse of the file as written; false, with the read's status set, when OCCT gives up.
        const auto parse_again = [&](StepReader& again) {
          const std::size_t first_message = guard.messages().size();
          if (again.ReadFile(path.c_str()) == IFSelect_RetDone) return true;
          const Status why = parse_failure(guard, first_message, "not a readable STEP file (second read)");
          fail(why.code, why.message);
          return false;
        };
        std::unique_ptr<StepReader> as_written;  // the file parsed as written, when a shortened list is not an assembly's
        StepReader* products_reader = &reader;
        if (mode == StepReadMode::Products || mode == StepReadMode::ProductsAsWritten) {
          ProductPlanResult plan = plan_products(reader, &shortened.removed);
          if (plan.needs_whole_text || (!plan.plan && shortened.changed())) {
            // A shortened list outside an assembly, or the XDE read to come
            // (its placements scan the lists): the file parsed as written.
            as_written = new_reader();
            if (parse_again(*as_written)) {
              xde_reader = as_written.get();
              if (plan.needs_whole_text) {
                products_reader = as_written.get();
                plan = plan_products(*as_written);
              }
            }
          }
          if (result.status.ok() && !plan.plan) {
            fall_back(plan.why_not);
          } else if (result.status.ok()) {
            result.assembly.reader = "products";
            ProductRead outcome;
            try {
              OCC_CATCH_SIGNALS
              outcome = read_products(*plan.plan, *products_reader, result.assembly, progress, 0.3, 1.0);
            } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& failure) {
              fail(StatusCode::ReadError, transfer_failure(failure, check));
            }
            if (result.status.ok() && outcome.outcome == ProductRead::Cancelled) fail(StatusCode::Cancelled, "cancelled");
            if (result.status.ok() && outcome.outcome == ProductRead::NotServed) {
              fall_back(outcome.why_not);
              reread = new_reader();
              if (result.status.ok()) parse_again(*reread);
              xde_reader = reread.get();
            } else if (result.status.ok()) {
              served = true;
              make_names_unique(result.assembly.bodies);
              if (result.assembly.bodies.empty())
                fail(StatusCode::InvalidInput, result.assembly.messages.empty()
                                                   ? "no solid in the file"
                                                   : "no solid in the file (" + result.assembly.messages.back() + ")");
            }
          }
        }
        if (result.status.ok() && !served) {
        result.assembly.reader = "xde";
        bool transferred = false;
        // OCCT's transfer is most of the read (quadratic on some chains of
        // references): its progress is the read's from 0.3 to 0.9, and
        // Cancel stops it.
        detail::CancelWatch watch(progress, "read");
        try {
          OCC_CATCH_SIGNALS
          Handle(detail::OcctBreak) indicator = new detail::OcctBreak(watch, 0.3, 0.9);
          transferred = xde_reader->Transfer(doc, indicator->Start());
        } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& failure) {
          fail(StatusCode::ReadError, transfer_failure(failure, check));
        }
        if (result.status.ok() && watch.cancelled()) fail(StatusCode::Cancelled, "cancelled");
        if (result.status.ok() && !transferred) {
          fail(StatusCode::ReadError, check.damaged_count ? "STEP transfer failed; damaged entities: " + describe_damaged(check)
                                                          : std::string("STEP transfer failed: no solid in the file"));
        }
        if (result.status.ok()) {
          Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
          TDF_LabelSequence roots;
          tool->GetFreeShapes(roots);
          StepTreeWalker walker(tool, result.assembly, progress, step_names(reader.ChangeReader().StepModel()));
          for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
            if (!walker.walk(roots.Value(i), TopLoc_Location(), "")) {
              result.status = Status::failure(StatusCode::Cancelled, "cancelled");
              break;
            }
          }
          make_names_unique(result.assembly.bodies);
          if (result.status.ok() && result.assembly.bodies.empty())
            fail(StatusCode::InvalidInput, result.assembly.messages.empty()
                                               ? "no solid in the file"
                                               : "no solid in the file (" + result.assembly.messages.back() + ")");
        }
        }
      }
      keep_reader_notes(guard, result.assembly.messages);
    }
  } catch (const Standard_OutOfMemory&) {
    fail(StatusCode::OutOfMemory, "out of memory while reading the STEP file");
  } catch (const std::bad_alloc&) {
    fail(StatusCode::OutOfMemory, "out of memory while reading the STEP file");
  } catch (const Standard_Failure& failure) {
    std::string message = std::string("OCCT ") + failure.DynamicType()->Name();
    if (failure.GetMessageString() && *failure.GetMessageString()) message += ": " + std::string(failure.GetMessageString());
    fail(StatusCode::ReadError, message + " while reading the STEP file");
  }
  try {
    if (!doc.IsNull()) app->Close(doc);
  } catch (const Standard_Failure&) {
    // A document half-filled by a failed transfer: nothing more to free safely.
  }
#ifdef __GLIBC__
  // The reader's model and the document are freed, but glibc keeps their
  // pages (tens of MB at 10,000 parts), and the partitions are made on worker
  // threads whose malloc arenas cannot reuse them: give them back, so the
  // pipeline's peak is the read's, not the read's plus the partitions'.
  malloc_trim(0);
#endif
  if (progress && result.status.ok()) progress->report("read", 1.0);
  return result;
}

Status shape_from_brep(const std::string& brep, TopoDS_Shape& shape) {
  const Status check = check_brep_text(brep);
  if (!check.ok()) return check;
  OcctGuard guard;
  try {
    OCC_CATCH_SIGNALS
    std::istringstream stream(brep);
    // OCCT 7.6's reader loops forever on a failed stream (a damaged number
    // in an edge record, found by make fuzz): a failed read throws instead.
    stream.exceptions(std::ios::failbit | std::ios::badbit);
    BRep_Builder builder;
    BRepTools::Read(shape, stream, builder);
  } catch (const Standard_OutOfMemory&) {
    return Status::failure(StatusCode::OutOfMemory, "out of memory while reading BRep");
  } catch (const Standard_Failure& failure) {
    const char* text = failure.GetMessageString();
    return Status::failure(StatusCode::InvalidInput, std::string("unreadable BRep: ") +
                                                         (text && *text ? text : failure.DynamicType()->Name()));
  } catch (const std::ios_base::failure&) {
    return Status::failure(StatusCode::InvalidInput, "unreadable BRep: damaged text (a value where OCCT's reader expects another)");
  }
  if (shape.IsNull()) return Status::failure(StatusCode::InvalidInput, "unreadable BRep: no shape");
  return Status::success();
}

std::string shape_to_brep(const TopoDS_Shape& shape) {
  std::ostringstream stream;
  BRepTools::Write(shape, stream);
  return stream.str();
}

AssemblyResult assembly_of_bodies(std::vector<Body> bodies, const std::vector<std::string>& names) {
  AssemblyResult result;
  if (bodies.size() != names.size()) {
    result.status = Status::failure(StatusCode::InvalidArgument,
                                    std::to_string(bodies.size()) + " bodies but " + std::to_string(names.size()) + " names");
    return result;
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].shape.IsNull()) {
      result.status = Status::failure(StatusCode::InvalidArgument, "a body without a shape");
      result.status.body = names[i];
      return result;
    }
    bodies[i].name = bodies[i].path = names[i];  // as bodies_from_brep names a child
  }
  result.assembly.bodies = std::move(bodies);
  make_names_unique(result.assembly.bodies);
  return result;
}

AssemblyResult bodies_from_brep(const std::string& brep, const std::vector<std::string>& names) {
  AssemblyResult result;
  TopoDS_Shape compound;
  result.status = shape_from_brep(brep, compound);
  if (!result.status.ok()) return result;
  const OcctGuard guard;  // the read shape explored: a signal inside OCCT is an error
  try {
    OCC_CATCH_SIGNALS
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
      if (!has_finite_box(children[i])) {
        result.status = Status::failure(StatusCode::InvalidInput,
                                        "coordinates that are not finite numbers (a NaN or infinite placement?)");
        result.status.body = name;
        return result;
      }
      // A face whose boundary does not close (a damaged wire record that lost
      // edges) makes OCCT's face-face intersection run forever, polling no
      // progress (make fuzz): refused here, before any Boolean meets it.
      const OpenWire open = find_open_wire(children[i]);
      if (open.face) {
        result.status = Status::failure(
            StatusCode::InvalidInput,
            "damaged topology: the face's boundary does not close (wire " + std::to_string(open.wire) + " has " +
                std::to_string(open.loose_ends) + " loose end(s)); OCCT's Booleans may never return on such a face");
        result.status.body = name;
        result.status.face = open.face;
        return result;
      }
      // Likewise a seam whose two curves on its face are one (a damaged edge record).
      const CollapsedSeam seam = find_collapsed_seam(children[i]);
      if (seam.face) {
        result.status = Status::failure(StatusCode::InvalidInput,
                                        "damaged topology: the seam edge " + std::to_string(seam.edge) +
                                            " has the same curve on both sides of the face; OCCT's Booleans may "
                                            "never return on such a face");
        result.status.body = name;
        result.status.face = seam.face;
        return result;
      }
    }
    make_names_unique(result.assembly.bodies);
  } catch (const Standard_OutOfMemory&) {
    result.status = Status::failure(StatusCode::OutOfMemory, "out of memory");
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::InvalidInput, "OCCT: " + occt_failure_text(failure));
  }
  return result;
}

MassProperties mass_properties(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return {props.Mass(), props.CentreOfMass()};
}

const MassProperties& Body::mass() const {
  // A fault inside OCCT leaves call_once by an exception (the flag stays
  // unset), never by the signal handler's jump, which would leave it taken.
  std::call_once(mass_cache->once, [this] {
    with_occt_signals([this] { mass_cache->value = mass_properties(shape); });
  });
  return mass_cache->value;
}

Status compute_mass_properties(const Assembly& assembly, int threads, Progress* progress) {
  const std::vector<Body>& bodies = assembly.bodies;
  const std::vector<int> sources = instance_sources(bodies);
  std::vector<std::string> failures(bodies.size());
  const OcctGuard guard;  // a fault in OCCT's integration fails that body
  if (!parallel_for(bodies.size(), threads, progress, "mass properties", [&](std::size_t i) {
        if (sources[i] == static_cast<int>(i)) run_guarded([&] { bodies[i].mass(); }, failures[i], "OCCT: ");
      }, 4))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (failures[i].empty()) continue;
    Status failed = Status::failure(StatusCode::GeometryError, "mass properties failed: " + failures[i]);
    failed.body = bodies[i].name;
    return failed;
  }
  if (!parallel_for(bodies.size(), threads, progress, "mass properties", [&](std::size_t i) {
        const int source = sources[i];
        if (source == static_cast<int>(i)) return;
        std::call_once(bodies[i].mass_cache->once, [&] {
          MassProperties moved = bodies[source].mass();  // a rigid motion keeps the volume
          moved.centre.Transform(relative_motion(bodies[source], bodies[i]));
          bodies[i].mass_cache->value = moved;
        });
      }, 64))
    return Status::failure(StatusCode::Cancelled, "cancelled");
  return Status::success();
}

TopoDS_Shape assembly_compound(const Assembly& assembly) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const Body& body : assembly.bodies) builder.Add(compound, body.shape);
  return compound;
}

}  // namespace contactcore
