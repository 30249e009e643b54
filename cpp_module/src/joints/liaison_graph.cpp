// The liaison graph as Graphviz DOT: bodies as nodes, joints as edges
// labelled "type (dof)", rigid groups as clusters.
#include <sstream>

#include "contactcore/joints/joints.h"

namespace contactcore {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

}  // namespace

std::string liaison_graph_dot(const Assembly& assembly, const JointsResult& joints,
                              const MobilityResult* mobility) {
  std::ostringstream dot;
  dot << "graph liaison {\n"
         "  graph [fontname=\"Helvetica\", fontsize=11, overlap=false, splines=true];\n"
         "  node [shape=box, style=\"rounded,filled\", fillcolor=\"#f4f4f4\", fontname=\"Helvetica\", fontsize=11];\n"
         "  edge [fontname=\"Helvetica\", fontsize=9];\n";
  const auto name = [&](int i) { return quoted(assembly.bodies[i].name); };
  std::vector<char> placed(assembly.bodies.size(), 0);
  if (mobility) {
    for (size_t g = 0; g < mobility->groups.size(); ++g) {
      const auto& group = mobility->groups[g];
      if (group.size() < 2 && !(mobility->ground >= 0 && group.front() == mobility->ground)) continue;
      const GroupMotion& motion = mobility->group_motions[g];
      std::string label = "group " + std::to_string(g + 1);
      if (mobility->ground >= 0 && g == 0) label += " (ground)";
      else label += ": " + std::string(to_string(motion.type)) + " (" + std::to_string(motion.dof) + ")";
      dot << "  subgraph cluster_" << g << " {\n    label=" << quoted(label)
          << "; style=\"rounded,dashed\"; color=\"#5070a0\"; fontname=\"Helvetica\";\n";
      for (int body : group) {
        dot << "    " << name(body);
        if (body == mobility->ground) dot << " [fillcolor=\"#d8e4f4\", peripheries=2]";
        dot << ";\n";
        placed[body] = 1;
      }
      dot << "  }\n";
    }
  }
  for (size_t i = 0; i < assembly.bodies.size(); ++i)
    if (!placed[i]) dot << "  " << name(static_cast<int>(i)) << ";\n";
  for (const PairJoint& j : joints.joints) {
    const bool rigid = j.type == JointType::Rigid;
    dot << "  " << name(j.body_a) << " -- " << name(j.body_b) << " [label="
        << quoted(std::string(to_string(j.type)) + " (" + std::to_string(j.dof) + ")");
    if (rigid) dot << ", penwidth=2";
    if (!j.stops.empty()) dot << ", style=dashed";  // can separate one way
    dot << "];\n";
  }
  dot << "}\n";
  return dot.str();
}

}  // namespace contactcore
