#include "stage_nodes.hpp"

#include <map>
#include <mutex>

namespace erkn::detail {
namespace {

// Stage i's nodes, most recent first: this step's stages j < i (at c_j), then those of the
// previous steps (at c_j - age); a node at the time of a more recent one is left out. Then the
// Lagrange weights at c_i on the first m nodes, for every m: node l's weight on m nodes,
// prod_{k < m, k != l} (c_i - t_k) / (t_l - t_k), is its weight on m - 1 nodes times the factor
// of node m - 1, the same product in the same order as formed anew, so the same bits: O(n^2)
// divisions rather than O(n^3). (Formed anew for every m, they and the nodes' times were ~5 % of
// the time of a construct + 1-step run of SERKN2s3 at P3: perf.)
void set_nodes(const double* c, int s, int i, StageNodes& out) {
  std::array<double, kMaxPredictorNodes> time;  // node l's time, c_j - age
  int& n = out.count[i];
  for (int age = 0; age <= kPredictorHistory; ++age)
    for (int j = (age == 0 ? i : s) - 1; j >= 0; --j) {
      const double t = c[j] - age;
      bool repeated = false;
      for (int l = 0; l < n; ++l) repeated |= time[l] == t;
      if (!repeated && n < kMaxPredictorNodes)
        out.offset[i][n] = age * s + j, out.nodes[i][n] = {age, j}, time[n++] = t;
    }
  const auto weight = [&](int m, int l) -> double& {
    return out.weights[(size_t(i) * out.n + m) * out.n + l];
  };
  for (int m = 1; m <= n; ++m) {
    const int k = m - 1;  // the node added
    double w = 1;         // its own weight
    for (int l = 0; l < k; ++l) {
      weight(k, l) = weight(k - 1, l) * ((c[i] - time[k]) / (time[l] - time[k]));
      w *= (c[i] - time[l]) / (time[k] - time[l]);
    }
    weight(k, k) = w;
  }
}

std::unique_ptr<const StageNodes> form(const Method& method) {
  auto out = std::make_unique<StageNodes>();
  const int s = method.stages();
  out->n = (kPredictorHistory + 1) * s;
  out->weights = std::make_unique<double[]>(size_t(s) * out->n * out->n);
  for (int i = 0; i < s; ++i) set_nodes(method.table().c, s, i, *out);
  return out;
}

}  // namespace

const StageNodes& stage_nodes(const Method& method) {
  // This thread's last answer (trivially destructible: read without an initialisation guard).
  thread_local const generated::Table* last_table = nullptr;
  thread_local const StageNodes* last = nullptr;
  if (last_table == &method.table()) return *last;
  // Keyed by the table (a method's own, outliving the program: Method::add). Never destroyed: an
  // Integrator that outlives the static destructors still reads its weights.
  static std::mutex* mutex = new std::mutex;
  static auto* formed = new std::map<const generated::Table*, std::unique_ptr<const StageNodes>>;
  std::lock_guard lock(*mutex);
  auto& nodes = (*formed)[&method.table()];
  if (!nodes) nodes = form(method);
  last_table = &method.table();
  last = nodes.get();
  return *nodes;
}

}  // namespace erkn::detail
