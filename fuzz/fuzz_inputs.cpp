#include "fuzz_inputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include <unistd.h>

#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <Standard_Failure.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/partitions/partitions.h"
#ifdef CONTACTS_WITH_HAPTICS
#include "contactcore/haptics/spacemouse.h"
#endif

namespace contactcore::fuzz {

namespace {

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz check failed: %s\n", what);
  std::abort();
}

void check_status(const Status& status) {
  if (!status.ok()) require(!status.message.empty(), "a failed Status without a message");
}

// Every face in exactly one partition, finite areas.
void check_partitions(const BodyPartitions& body) {
  check_status(body.status);
  if (!body.status.ok()) return;
  std::vector<int> owner(body.faces.size() + 1, 0);
  for (const Partition& partition : body.partitions) {
    require(std::isfinite(partition.area) && partition.area >= 0, "partition area not finite or negative");
    for (int face : partition.faces) {
      require(face >= 1 && face <= static_cast<int>(body.faces.size()), "partition names a face that does not exist");
      require(++owner[face] == 1, "face in two partitions");
    }
  }
  for (std::size_t face = 1; face < owner.size(); ++face) require(owner[face] == 1, "face in no partition");
}

// Contacts and interferences name real bodies (a < b) and partitions, with finite areas and volumes.
void check_contacts(const Assembly& assembly, const ContactsResult& result) {
  check_status(result.status);
  if (!result.status.ok()) return;
  const int bodies = static_cast<int>(assembly.bodies.size());
  require(result.partitions.size() == assembly.bodies.size(), "one partition list per body");
  for (const BodyPartitions& body : result.partitions) check_partitions(body);
  const auto partition_exists = [&](int body, int partition) {
    return partition >= 0 && partition < static_cast<int>(result.partitions[body].partitions.size());
  };
  for (const Contact& contact : result.contacts) {
    require(contact.body_a >= 0 && contact.body_a < contact.body_b && contact.body_b < bodies, "contact bodies");
    require(partition_exists(contact.body_a, contact.partition_a) && partition_exists(contact.body_b, contact.partition_b),
            "contact partitions");
    require(std::isfinite(contact.area) && contact.area >= 0, "contact area not finite or negative");
    require(!contact.faces_a.empty() && !contact.faces_b.empty(), "contact without faces");
  }
  for (const Interference& interference : result.interferences) {
    require(interference.body_a >= 0 && interference.body_a < interference.body_b && interference.body_b < bodies,
            "interference bodies");
    require(std::isfinite(interference.volume) && interference.volume >= 0, "interference volume not finite or negative");
  }
  for (const SkippedPair& skipped : result.skipped) require(!skipped.message.empty(), "skipped pair without a message");
}

// Serially, as the CLI and the workbench run it.
void find_and_check_contacts(const Assembly& assembly) {
  ContactOptions options;
  options.threads = 1;
  check_contacts(assembly, find_contacts(assembly, options));
}

const std::string& step_input_path() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    std::string p = std::string(dir && *dir ? dir : "/tmp") + "/contacts_fuzz_" + std::to_string(getpid()) + ".step";
    std::atexit([] { std::remove(step_input_path().c_str()); });
    return p;
  }();
  return path;
}

}  // namespace

void run_step_input(const std::uint8_t* data, std::size_t size) {
  const std::string& path = step_input_path();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  require(file != nullptr, "cannot write the temporary STEP file");
  if (size) require(std::fwrite(data, 1, size, file) == size, "cannot write the temporary STEP file");
  std::fclose(file);
  const AssemblyResult read = read_step(path);
  check_status(read.status);
  if (!read.status.ok()) return;
  require(!read.assembly.bodies.empty(), "a STEP read that succeeds has bodies");
  find_and_check_contacts(read.assembly);
}

void run_brep_input(const std::uint8_t* data, std::size_t size) {
  const std::string brep(reinterpret_cast<const char*>(data), size);
  try {  // as bindings/common.h `guarded` around partition_brep
    TopoDS_Shape shape;
    const Status read = shape_from_brep(brep, shape);
    check_status(read);
    if (read.ok()) {
      Bnd_Box box;
      BRepBndLib::Add(shape, box);
      const Tolerances tolerances = resolve_tolerances(box, {}, {});
      const Status valid = check_tolerances(box, tolerances);
      check_status(valid);
      if (valid.ok()) check_partitions(partition_shape(shape, tolerances));
    }
  } catch (const Standard_Failure&) {
  } catch (const std::exception&) {
  }
  const AssemblyResult bodies = bodies_from_brep(brep, {});
  check_status(bodies.status);
  if (bodies.status.ok() && !bodies.assembly.bodies.empty()) find_and_check_contacts(bodies.assembly);
}

#ifdef CONTACTS_WITH_HAPTICS
void run_hid_input(const std::uint8_t* data, std::size_t size) {
  using namespace contactcore::haptics;
  if (size < 2) return;
  const auto& models = known_models();
  const std::size_t pick = data[0] % (models.size() + 2);
  const SpaceMouseModel model = pick < models.size()    ? models[pick]
                                : pick == models.size() ? generic_model(0x046d, 0xc6ff)
                                                        : generic_model(0x256f, 0xc6ff);
  const std::uint8_t* rest = data + 2;
  std::size_t left = size - 2;
  if (data[1] & 1) {
    (void)descriptor_has_pid_page(rest, left);
    return;
  }
  SpaceMouseState state;
  while (left > 0) {
    const std::size_t length = std::min<std::size_t>(rest[0], left - 1);
    const SpaceMouseState before = state;
    if (parse_report(rest + 1, length, model, state)) {
      require(state.reports == before.reports + 1, "an understood report is counted");
      for (int i = 0; i < 6; ++i)
        require(std::isfinite(state.axes[i]) && std::abs(state.axes[i]) <= 1.0, "axes normalised to [-1, 1]");
    } else {
      require(state.reports == before.reports && state.buttons == before.buttons &&
                  std::equal(state.raw, state.raw + 6, before.raw),
              "a report not understood leaves the state unchanged");
    }
    rest += 1 + length;
    left -= 1 + length;
  }
}
#endif

}  // namespace contactcore::fuzz
