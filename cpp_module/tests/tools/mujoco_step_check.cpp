// Loads an MJCF file in MuJoCo, steps it with constant generalized forces on
// named joints and prints the joints' positions and the bodies' poses before
// and after, as JSON (tests/test_mechanism_export.py checks the export with it).
//   mujoco_step_check MODEL.xml STEPS [JOINT=FORCE ...]
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace {

void print_bodies(const mjModel* m, const mjData* d) {
  std::printf("[");
  for (int b = 0; b < m->nbody; ++b) {
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    std::printf("%s{\"name\": \"%s\", \"xpos\": [%.17g, %.17g, %.17g], \"xquat\": [%.17g, %.17g, %.17g, %.17g]}",
                b ? ", " : "", name ? name : "", d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2],
                d->xquat[4 * b], d->xquat[4 * b + 1], d->xquat[4 * b + 2], d->xquat[4 * b + 3]);
  }
  std::printf("]");
}

void print_joints(const mjModel* m, const mjData* d) {
  std::printf("[");
  for (int j = 0; j < m->njnt; ++j) {
    const char* name = mj_id2name(m, mjOBJ_JOINT, j);
    const int type = m->jnt_type[j];
    const int size = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
    std::printf("%s{\"name\": \"%s\", \"type\": %d, \"qpos\": [", j ? ", " : "", name ? name : "", type);
    for (int k = 0; k < size; ++k) std::printf("%s%.17g", k ? ", " : "", d->qpos[m->jnt_qposadr[j] + k]);
    std::printf("]}");
  }
  std::printf("]");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MODEL.xml STEPS [JOINT=FORCE ...]\n", argv[0]);
    return 2;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "MuJoCo could not load '%s': %s\n", argv[1], error);
    return 3;
  }
  const long steps = std::strtol(argv[2], nullptr, 10);
  std::vector<std::pair<int, double>> forces;  // dof address, force or torque
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    const int joint = eq == std::string::npos ? -1 : mj_name2id(m, mjOBJ_JOINT, arg.substr(0, eq).c_str());
    if (joint < 0) {
      std::fprintf(stderr, "no joint '%s' in the model\n", arg.c_str());
      mj_deleteModel(m);
      return 2;
    }
    forces.emplace_back(m->jnt_dofadr[joint], std::strtod(arg.c_str() + eq + 1, nullptr));
  }
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  std::printf("{\"nq\": %d, \"nv\": %d, \"njnt\": %d, \"nbody\": %d, \"timestep\": %.17g, \"gravity\": [%.17g, %.17g, %.17g],\n",
              m->nq, m->nv, m->njnt, m->nbody, m->opt.timestep, m->opt.gravity[0], m->opt.gravity[1],
              m->opt.gravity[2]);
  std::printf(" \"body_mass\": [");
  for (int b = 0; b < m->nbody; ++b) std::printf("%s%.17g", b ? ", " : "", m->body_mass[b]);
  std::printf("],\n \"before\": {\"bodies\": ");
  print_bodies(m, d);
  std::printf(", \"joints\": ");
  print_joints(m, d);
  std::printf("},\n");
  for (long s = 0; s < steps; ++s) {
    mju_zero(d->qfrc_applied, m->nv);
    for (const auto& [dof, force] : forces) d->qfrc_applied[dof] = force;
    mj_step(m, d);
  }
  mj_forward(m, d);
  std::printf(" \"after\": {\"bodies\": ");
  print_bodies(m, d);
  std::printf(", \"joints\": ");
  print_joints(m, d);
  std::printf("}}\n");
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
