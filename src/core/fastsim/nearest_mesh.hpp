/// The FastSim mesh a per-mesh table serves a model on (ChiTable, CalibrationTable): both are
/// identified per nodes per strip nx, because they absorb the march's discretisation along the
/// strips.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace wheel_rail_contact {

/// Of `meshes` (non-empty, sorted by increasing nx, each with a member nx), the one nearest nx
/// nodes per strip in 1/nx (the march's step along the strip); a tie goes to the finer mesh.
template <class Mesh>
const Mesh& nearestMesh(const std::vector<Mesh>& meshes, int nx) {
  const Mesh* best = &meshes.front();
  for (const Mesh& m : meshes)  // increasing nx: the last of the equally near ones is the finer
    if (std::abs(1.0 / m.nx - 1.0 / nx) <= std::abs(1.0 / best->nx - 1.0 / nx)) best = &m;
  return *best;
}

/// Where nx lies strictly between two of `meshes` (sorted by increasing nx, none of them nx = 0,
/// "any"): the two neighbours and nx's place w in [0, 1] between them in 1/nx (the march's step
/// along the strip). False on an identified mesh or beyond the table's meshes: nearestMesh.
template <class Mesh>
bool meshesAround(const std::vector<Mesh>& meshes, int nx, const Mesh** lo, const Mesh** hi,
                  double* w) {
  std::size_t i = 0;
  while (i + 1 < meshes.size() && meshes[i + 1].nx <= nx) ++i;
  if (i + 1 >= meshes.size() || meshes[i].nx == 0 || nx <= meshes[i].nx) return false;
  *lo = &meshes[i];
  *hi = &meshes[i + 1];
  *w = (1.0 / (*lo)->nx - 1.0 / nx) / (1.0 / (*lo)->nx - 1.0 / (*hi)->nx);
  return true;
}

/// Sorts `meshes` by increasing nx, as nearestMesh needs them.
template <class Mesh>
void sortByNodes(std::vector<Mesh>* meshes) {
  std::sort(meshes->begin(), meshes->end(),
            [](const Mesh& x, const Mesh& y) { return x.nx < y.nx; });
}

/// The nx of each of `meshes`, in their order.
template <class Mesh>
std::vector<int> nodeCounts(const std::vector<Mesh>& meshes) {
  std::vector<int> nx;
  for (const Mesh& m : meshes) nx.push_back(m.nx);
  return nx;
}

}  // namespace wheel_rail_contact
